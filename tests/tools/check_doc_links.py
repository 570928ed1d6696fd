#!/usr/bin/python3
"""Every relative link in README.md and docs/*.md resolves, and every citation of
docs/DESIGN.md §N in the sources names a section that exists.

Links: [text](target) where target is not a URL; the file must exist (relative to the
document) and a #fragment must match a heading of the target as GitHub renders its anchor.
Citations: "DESIGN.md §N" or "§N.M" in src/, tests/, tools/, lmp_inputs/, cases/ and in the
documents must match a "## N." / "### N.M" heading of docs/DESIGN.md.

Usage: check_doc_links.py REPOSITORY_ROOT
Exit 0 when everything resolves; 1 with one line per broken link or citation.
"""
import pathlib
import re
import sys

LINK = re.compile(r"(?<!!)\[[^\]]*\]\(([^)\s]+)\)|!\[[^\]]*\]\(([^)\s]+)\)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
CITATION = re.compile(r"DESIGN\.md\s*§\s*(\d+(?:\.\d+)*)")
SECTION = re.compile(r"^#{2,4}\s+(\d+(?:\.\d+)*)\.?\s")
CODE_FENCE = re.compile(r"^\s*(```|~~~)")


def headings(text):
    """Heading lines outside fenced code blocks."""
    fenced = False
    for line in text.splitlines():
        if CODE_FENCE.match(line):
            fenced = not fenced
            continue
        if not fenced:
            m = HEADING.match(line)
            if m:
                yield m.group(2)


def github_anchor(heading):
    """The anchor GitHub gives a heading: lower case, punctuation dropped, spaces to '-'."""
    text = re.sub(r"`", "", heading).strip().lower()
    text = "".join(c for c in text if c.isalnum() or c in " -_")
    return text.replace(" ", "-")


def anchors(path, cache={}):
    if path not in cache:
        seen, result = {}, set()
        for h in headings(path.read_text(encoding="utf-8")):
            a = github_anchor(h)
            n = seen.get(a, 0)
            seen[a] = n + 1
            result.add(a if n == 0 else f"{a}-{n}")
        cache[path] = result
    return cache[path]


def links(text):
    fenced = False
    for number, line in enumerate(text.splitlines(), 1):
        if CODE_FENCE.match(line):
            fenced = not fenced
            continue
        if fenced:
            continue
        # Inline code spans are not links.
        line = re.sub(r"`[^`]*`", "", line)
        for m in LINK.finditer(line):
            yield number, m.group(1) or m.group(2)


def check_document(doc, root):
    problems = []
    for number, target in links(doc.read_text(encoding="utf-8")):
        if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
            continue
        file_part, _, fragment = target.partition("#")
        dest = (doc.parent / file_part).resolve() if file_part else doc.resolve()
        where = f"{doc.relative_to(root)}:{number}: {target}"
        if not dest.exists():
            problems.append(f"{where}: no such file")
        elif fragment and dest.suffix == ".md" and fragment not in anchors(dest):
            problems.append(f"{where}: no heading with anchor #{fragment} in {dest.name}")
    return problems


def design_sections(design):
    sections = set()
    for h in headings(design.read_text(encoding="utf-8")):
        m = SECTION.match("## " + h)
        if m:
            sections.add(m.group(1))
    return sections


def check_citations(root, sections):
    problems = []
    files = [p for d in ("src", "tests", "tools", "lmp_inputs", "cases") for p in (root / d).rglob("*")
             if p.is_file()]
    files += [root / "README.md"] + sorted((root / "docs").glob("*.md"))
    for path in files:
        try:
            text = path.read_text(encoding="utf-8")
        except (UnicodeDecodeError, OSError):
            continue  # pictures, binaries
        for number, line in enumerate(text.splitlines(), 1):
            for m in CITATION.finditer(line):
                if m.group(1) not in sections:
                    problems.append(f"{path.relative_to(root)}:{number}: DESIGN.md §{m.group(1)}: "
                                    "no such section in docs/DESIGN.md")
    return problems


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    root = pathlib.Path(sys.argv[1]).resolve()
    documents = [root / "README.md"] + sorted((root / "docs").glob("*.md"))
    problems = []
    for doc in documents:
        problems += check_document(doc, root)
    design = root / "docs" / "DESIGN.md"
    if not design.exists():
        problems.append("docs/DESIGN.md: missing")
    else:
        sections = design_sections(design)
        if not sections:
            problems.append("docs/DESIGN.md: no numbered sections")
        problems += check_citations(root, sections)
    for p in problems:
        print(p)
    print(f"{len(documents)} documents checked, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
