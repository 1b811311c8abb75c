"""`python -m tendonsheath`: the same command as `tendonsheath`."""

from .apps.cli import main

# guarded: the sweep's worker processes import the main module again (spawn, forkserver), and
# an unguarded main() would refuse the demo's robustness sweep or start it in every worker
if __name__ == "__main__":
    main()
