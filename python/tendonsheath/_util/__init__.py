"""Private helpers every layer may use (argument checks, arrays, atomic writes, progress, jobs,
units): not part of the public API."""
