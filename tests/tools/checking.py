"""What the tool check scripts share: `check` prints ok/FAIL and keeps the failures, `tool`
runs a checkout's tools/NAME.py with this Python, `finish` reports and exits."""
import os
import subprocess
import sys

TOOLS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools")

failures = []


def check(condition, message):
    print(("ok   " if condition else "FAIL ") + message)
    if not condition:
        failures.append(message)


def tool(name, args):
    """(exit code, stdout, stderr) of tools/`name` with `args`."""
    p = subprocess.run([sys.executable, os.path.join(TOOLS, name)] + args, capture_output=True,
                       text=True)
    return p.returncode, p.stdout, p.stderr


def finish():
    print(f"{len(failures)} failure(s)")
    sys.exit(1 if failures else 0)
