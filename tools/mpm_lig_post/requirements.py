"""The Python packages the tools need, checked before anything else is imported: a Python
without one of them (a virtual environment, a module system) gets one line naming what is
missing and how to install it, and exit code 2, instead of an ImportError traceback."""
import importlib
import os
import signal
import sys

# import name -> Debian package (the pip names are the import names: tools/requirements.txt)
DEBIAN = {"numpy": "python3-numpy", "h5py": "python3-h5py", "matplotlib": "python3-matplotlib"}
REQUIREMENTS_TXT = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                "requirements.txt")


def missing(packages):
    """The names of `packages` this Python cannot import (any failure counts, not only
    ImportError: a package built for another Python raises other errors). Ctrl-C while they
    load raises KeyboardInterrupt, also where a package's own start turns it into an
    ImportError (numpy's C start-up, which loses the interrupt)."""
    signalled = []

    def note_and_stop(signum, frame):
        signalled.append(signum)
        raise KeyboardInterrupt

    # Only where Ctrl-C would interrupt anyway (not in a job started with SIGINT ignored),
    # and only the main thread may set a handler.
    watch = signal.getsignal(signal.SIGINT) is signal.default_int_handler
    if watch:
        try:
            signal.signal(signal.SIGINT, note_and_stop)
        except ValueError:
            watch = False
    out = []
    try:
        for name in packages:
            try:
                importlib.import_module(name)
            # Any failure: the reason does not matter to the user, the name does.
            except Exception:  # noqa: BLE001
                if signalled:
                    raise KeyboardInterrupt from None
                out.append(name)
    finally:
        if watch:
            signal.signal(signal.SIGINT, signal.default_int_handler)
    return out


def install_hint(names):
    """How to install the packages `names`: Debian packages or pip with the requirements file."""
    debian = " ".join(DEBIAN[n] for n in names)
    return (f"install the Debian packages (apt-get install {debian}) or, in a virtual "
            f"environment, pip install -r {REQUIREMENTS_TXT}")


def require(*packages):
    """Exit 2 with one line on stderr when this Python lacks any of `packages`."""
    lacking = missing(packages)
    if lacking:
        tool = os.path.basename(sys.argv[0]) or "mpm_lig tools"
        print(f"{tool}: error: {sys.executable} lacks the Python package(s) "
              f"{', '.join(lacking)}: {install_hint(lacking)}", file=sys.stderr)
        sys.exit(2)
