"""How a checkout's tools/NAME.py starts its command. Loading a command takes a quarter second
(numpy, matplotlib): this module imports nothing that Python has not loaded at its start, and
everything else inside `command`, so that Ctrl-C while the command loads ends as it does later
in `cli.run`, with 'tool: interrupted' and exit code 130. (Python's own start, the first few
hundredths of a second, is beyond reach.)"""
import importlib
import os
import sys

INTERRUPTED = 130  # 128 + SIGINT, what a shell reports for Ctrl-C


def tool_name():
    return os.path.basename(sys.argv[0]) or "tool"


def interrupted():
    """Ctrl-C: one line on stderr, exit code 130."""
    print(f"{tool_name()}: interrupted", file=sys.stderr)
    sys.exit(INTERRUPTED)


def command(name, needs=()):
    """Run mpm_lig_post.commands.`name`'s entry(), after checking the packages `needs` (for
    a command whose module imports them before checking them itself: a Python without them
    is told so in one line, requirements.py). entry() runs the command in cli.run; what it
    imports before that is covered here."""
    try:
        from .requirements import require

        require(*needs)
        importlib.import_module(f"mpm_lig_post.commands.{name}").entry()
    except KeyboardInterrupt:
        interrupted()
