"""Shared helpers of the Python tests: record failures, report them at the end."""
import sys

failures = 0


def check(cond, what):
    """Records a failure (and prints `what`) unless `cond` holds."""
    global failures
    if not cond:
        failures += 1
        print("FAILED:", what)


def finish(exit_on_success=True):
    """Prints the count; exits 1 on failure. pvbatch under MPI must end normally on
    success (exit_on_success=False) so that it finalizes MPI on every rank."""
    print("%d failures" % failures)
    if failures:
        sys.exit(1)
    if exit_on_success:
        sys.exit(0)
