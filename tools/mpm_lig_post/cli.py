"""Command-line frame shared by the plot tools: `plot_X.py OUTPUT_DIR [-o picture.png]`."""
import argparse
import os
import sys

from .errors import InputError


def parser(description, default_png):
    """An ArgumentParser with the positional OUTPUT_DIR and -o/--output."""
    p = argparse.ArgumentParser(description=description)
    p.add_argument("output_dir", metavar="OUTPUT_DIR", help="the run's output directory")
    p.add_argument("-o", "--output", metavar="PNG",
                   help=f"picture to write (default OUTPUT_DIR/{default_png})")
    p.add_argument("--dpi", type=int, default=200,
                   help="picture resolution in dots per inch (default 200, print quality)")
    p.set_defaults(default_png=default_png)
    return p


def output_dir(args):
    """The OUTPUT_DIR argument, checked."""
    if not os.path.isdir(args.output_dir):
        raise InputError(f"{args.output_dir}: no such output directory")
    return args.output_dir


def picture_path(args):
    """Where the picture goes: -o, or OUTPUT_DIR/<default name>."""
    return args.output or os.path.join(args.output_dir, args.default_png)


def run(main):
    """Call main(); bad input ends with 'tool: error: ...' on stderr and exit code 2
    (argparse's own usage errors exit 2 as well)."""
    tool = os.path.basename(sys.argv[0])
    try:
        main()
    except InputError as e:
        print(f"{tool}: error: {e}", file=sys.stderr)
        sys.exit(2)
