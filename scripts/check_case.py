#!/usr/bin/env python3
"""Checks cases before running them: `mmcontact -check_input` on each options file.

    /usr/bin/python3 -s scripts/check_case.py [--np N] options/CASE.opts [more.opts ...] [-- mmcontact options]

mmcontact itself is the one source of truth (README "Checking a case before a batch job"): it reads
the options and the mesh, builds the case as a run does, refuses what a run would refuse (same
message, exit status 64), and prints the start-up report with each physical group's node and
element counts, the contact nodes and smallest gap per obstacle and pair, c_p dt / h_c', the planned
steps and output size and a first-contact estimate, without stepping or writing anything. This
script only runs it for each file, from the current directory (the options' paths are relative to
it), on N ranks through mpiexec with --np, and exits with the first non-zero status, 0 if every case
is valid.
"""
import argparse
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main(argv):
    extra = []
    if "--" in argv:
        extra, argv = argv[argv.index("--") + 1:], argv[:argv.index("--")]
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("options", nargs="+", help="options files of the cases")
    ap.add_argument("--np", type=int, default=0, help="ranks (mpiexec); 0: the executable alone, one rank")
    ap.add_argument("--exe", default=os.path.join(ROOT, "mmcontact"), help="the mmcontact executable")
    args = ap.parse_args(argv)
    launcher = []
    if args.np > 0:
        launcher = ["mpiexec", "-n", str(args.np)] + (["--allow-run-as-root"] if os.geteuid() == 0 else [])
    status = 0
    for path in args.options:
        print(f"== {path}", flush=True)
        rc = subprocess.run(launcher + [args.exe, "-options_file", path, "-check_input", *extra]).returncode
        status = status or rc
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
