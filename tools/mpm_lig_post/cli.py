"""Command-line frame shared by the tools: the argument parser (one-line usage errors, checked
numbers), output paths checked before the work, and `run`, which turns bad input, Ctrl-C and
a closed pipe into one line on stderr and an exit code instead of a traceback."""
import argparse
import math
import os
import sys
import tempfile

from .errors import InputError
from .launch import interrupted, tool_name


class ArgumentParser(argparse.ArgumentParser):
    """argparse with a usage error on one line: 'tool: error: ... (see --help)', exit 2."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} (see --help)\n")


def parser(description, default_png):
    """An ArgumentParser with the positional OUTPUT_DIR, -o/--output and --dpi."""
    p = ArgumentParser(description=description)
    p.add_argument("output_dir", metavar="OUTPUT_DIR", help="the run's output directory")
    p.add_argument("-o", "--output", metavar="PNG",
                   help=f"picture to write (default OUTPUT_DIR/{default_png})")
    p.add_argument("--dpi", type=dpi, default=200,
                   help="picture resolution in dots per inch (default 200, print quality)")
    p.set_defaults(default_png=default_png)
    return p


def number(kind, test, wanted):
    """An argparse type: `kind`(text), finite and passing `test`, else a usage error saying
    that it must be `wanted`."""
    def convert(text):
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"'{text}' is not a number") from None
        if not (math.isfinite(value) and test(value)):
            raise argparse.ArgumentTypeError(f"{text}: must be {wanted}")
        return value
    convert.__name__ = wanted  # argparse names the type in its messages
    return convert


positive = number(float, lambda x: x > 0, "a finite number > 0")
non_negative = number(float, lambda x: x >= 0, "a finite number >= 0")
finite = number(float, lambda x: True, "a finite number")
positive_int = number(int, lambda x: x > 0, "an integer > 0")
non_negative_int = number(int, lambda x: x >= 0, "an integer >= 0")
# Picture resolution: below 10 nothing is legible, above 2400 a page-sized figure does not fit
# in memory.
dpi = number(int, lambda x: 10 <= x <= 2400, "an integer 10 ... 2400")


def output_dir(args):
    """The OUTPUT_DIR argument, checked, and the picture's path (before any work)."""
    if not os.path.isdir(args.output_dir):
        raise InputError(f"{args.output_dir}: no such output directory")
    picture_file(picture_path(args))
    return args.output_dir


# What matplotlib's Agg and vector back ends write (a name without a suffix is a PNG).
PICTURE_FORMATS = ("png", "pdf", "svg", "svgz", "eps", "ps", "jpg", "jpeg", "tif", "tiff",
                   "webp", "pgf", "raw", "rgba")


def picture_file(path):
    """writable_file for a picture, whose suffix must be a format matplotlib writes."""
    suffix = os.path.splitext(path)[1][1:].lower()
    if suffix and suffix not in PICTURE_FORMATS:
        raise InputError(f"{path}: cannot write a picture of format '{suffix}' (give one of "
                         f"{', '.join(PICTURE_FORMATS[:5])}, ...)")
    return writable_file(path, "picture")


def writable_file(path, what="output"):
    """Check, before any work, that `path` can be written: its folder exists and is writable
    and it is not a folder itself. Returns the path (None stays None)."""
    if path is None:
        return None
    if not path:
        raise InputError(f"the {what}: an empty file name")
    folder = os.path.dirname(os.path.abspath(path))
    if os.path.isdir(path):
        raise InputError(f"{path}: {what} is a folder, not a file")
    if not os.path.isdir(folder):
        raise InputError(f"{path}: cannot write the {what}: folder {folder} does not exist")
    if not _can_create_in(folder) or (os.path.exists(path) and not os.access(path, os.W_OK)):
        raise InputError(f"{path}: cannot write the {what}: no permission")
    return path


def _can_create_in(folder):
    """Whether a file can be created in `folder`, tried (and gone at once): os.access trusts
    the mode bits, which root overrides, while /proc or a read-only mount refuses root too."""
    try:
        with tempfile.TemporaryFile(dir=folder):
            return True
    except OSError:
        return False


def writable_folder(path, what="output folder"):
    """Check, before any work, that the folder `path` exists or can be created there."""
    if os.path.exists(path) and not os.path.isdir(path):
        raise InputError(f"{path}: the {what} is a file, not a folder")
    parent = os.path.abspath(path)
    while not os.path.exists(parent):
        parent = os.path.dirname(parent)
    if not os.path.isdir(parent) or not _can_create_in(parent):
        raise InputError(f"{path}: cannot create or write the {what} ({parent} is not a "
                         "writable folder)")
    return path


def picture_path(args):
    """Where the picture goes: -o, or OUTPUT_DIR/<default name>."""
    return args.output or os.path.join(args.output_dir, args.default_png)


def run(main, failures=()):
    """Call main() and exit with what it returns (0 for None). Bad input ends with
    'tool: error: ...' on stderr and exit code 2 (argparse's usage errors exit 2 as well);
    an exception of the types `failures` (a run that failed) with 'tool: ...' and 1;
    Ctrl-C with 'tool: interrupted' and 130; a closed output pipe (tool | head) quietly."""
    tool = tool_name()
    try:
        code = main()
    except failures as e:
        print(f"{tool}: {e}", file=sys.stderr)
        sys.exit(1)
    except InputError as e:
        print(f"{tool}: error: {e}", file=sys.stderr)
        sys.exit(2)
    except KeyboardInterrupt:
        interrupted()
    except BrokenPipeError:
        # The reader went away: nothing more to say to it. Point stdout at /dev/null so
        # that the interpreter's final flush does not complain.
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        sys.exit(1)
    sys.exit(code or 0)
