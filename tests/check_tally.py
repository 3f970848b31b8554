"""The tally of the readers' checks (tests/ase_check.py, tests/gsd_check.py): check() counts a
check and prints "FAILED: what" when it fails; done() prints "N passed, M failed" and exits 1 on
a failure, else 0.  Imported from the script's own folder (sys.path[0])."""
import sys

passed = failed = 0


def check(ok, what):
    global passed, failed
    if ok:
        passed += 1
    else:
        failed += 1
        print("FAILED:", what)


def done():
    print("%d passed, %d failed" % (passed, failed))
    sys.exit(1 if failed else 0)
