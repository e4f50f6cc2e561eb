"""What the peer scripts of bench/peer share: reading the Matrix Market files
femup writes, measuring the peak resident set of the process, and printing
the result as one JSON object.

Imported by the scripts next to it (their directory is on sys.path when they
run as scripts). Needs numpy and scipy; the scripts check the import first.
"""

import json
import resource
import sys

import numpy as np
import scipy
import scipy.io
import scipy.sparse


def read_vector(path):
    """A Matrix Market vector (array n x 1) as a 1-D float array."""
    return np.asarray(scipy.io.mmread(path), dtype=float).ravel()


def read_dense(path):
    """A Matrix Market matrix (array or coordinate) as a dense float array."""
    matrix = scipy.io.mmread(path)
    if scipy.sparse.issparse(matrix):
        matrix = matrix.toarray()
    return np.asarray(matrix, dtype=float)


def read_csc(path):
    """A Matrix Market matrix as a scipy CSC matrix of floats (symmetric files
    are expanded to full storage by mmread)."""
    return scipy.sparse.csc_matrix(scipy.io.mmread(path), dtype=float)


def status_mb(field):
    """VmRSS / VmHWM of this process from /proc/self/status, MB; None if unreadable."""
    try:
        with open("/proc/self/status") as status:
            for line in status:
                if line.startswith(field + ":"):
                    return int(line.split()[1]) / 1024.0
    except OSError:
        pass
    return None


def reset_peak_rss():
    """Resets VmHWM to the current RSS (Linux >= 4.0); False when not possible."""
    try:
        with open("/proc/self/clear_refs", "w") as clear:
            clear.write("5")
        return True
    except OSError:
        return False


def maxrss_mb():
    """The whole process's peak resident set so far, MB (ru_maxrss is in kB on Linux)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def print_result(fields, memory=None):
    """Prints one JSON object on stdout: scipy's and numpy's versions, then
    `fields`, then, with memory=(rss_before_solve_mb, solve_peak_rss_mb), those
    two and maxrss_mb."""
    result = {"scipy": scipy.__version__, "numpy": np.__version__}
    result.update(fields)
    if memory is not None:
        result.update({
            "rss_before_solve_mb": memory[0],
            "solve_peak_rss_mb": memory[1],
            "maxrss_mb": maxrss_mb(),
        })
    json.dump(result, sys.stdout)
    sys.stdout.write("\n")
