"""What the peer scripts of bench/peer share: reading the Matrix Market files
femup writes, and measuring the peak resident set of the process.

Imported by the scripts next to it (their directory is on sys.path when they
run as scripts). Needs numpy and scipy; the scripts check the import first.
"""

import resource

import numpy as np
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
