"""`python -m tendonsheath`: the same command as `tendonsheath`."""

from .cli import main

main()
