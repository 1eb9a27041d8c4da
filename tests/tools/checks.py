"""What the Python CTest checkers of tests/tools share: the skip exit code and
failing with a message (a checker's exit is 0 pass, 1 fail, 77 skip)."""
import sys

SKIP = 77


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def check(cond, msg):
    if not cond:
        fail(msg)
