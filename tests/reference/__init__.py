"""Independent references and stand-ins for the tests and the benchmarks; not shipped in the
package. The benchmarks put ``tests/`` on ``sys.path`` (``benchmarks/_common.py``)."""
