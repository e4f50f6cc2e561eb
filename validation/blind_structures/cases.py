"""What every blind suite's case generator does alike: the effect's size drawn
in noise units and found by bisection, the measurement noise added, and the
study's measurements and diagnosis written as YAML."""
import math

import numpy as np


def draw_target(rng):
    """The largest relative frequency shift an effect is to cause, in noise
    units: log-uniform in [5, 50] for four cases in five, [1, 5] otherwise."""
    strong = rng.random() < 0.8
    return math.exp(rng.uniform(math.log(5), math.log(50)) if strong else
                    rng.uniform(0, math.log(5)))


def size_for_shift(shift, a_max, target):
    """The effect size a in [0, a_max] whose shift(a) (monotone, in noise units)
    reaches `target`, by bisection; a_max where even it falls short."""
    if shift(a_max) <= target:
        return a_max
    lo, hi = 0.0, a_max
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        if shift(mid) < target:
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-4 * a_max:
            break
    return 0.5 * (lo + hi)


def largest_shift(f, f0, fnoise):
    """The largest relative frequency shift of f against f0, in noise units."""
    return float(np.max(np.abs(f / f0 - 1))) / fnoise


def measured(rng, freqs, shape_rows, fnoise, snoise, noise_free):
    """Frequencies times (1 + fnoise N(0,1)) and shape rows (already scaled to a
    largest entry of 1) plus snoise N(0,1); with noise_free the draws are made
    but not added, so every case stays the same as with noise."""
    fn = rng.standard_normal(len(freqs))
    sn = rng.standard_normal((len(freqs), len(shape_rows[0])))
    scale = 0.0 if noise_free else 1.0
    noisy_f = np.asarray(freqs) * (1 + scale * fnoise * fn)
    rows = [(np.asarray(s) + scale * snoise * sn[k]).tolist() for k, s in enumerate(shape_rows)]
    return noisy_f.tolist(), rows


def yaml_list(values):
    """A YAML flow list of numbers, to 10 significant digits."""
    return "[" + ", ".join("%.10g" % x for x in values) + "]"


def measurements_yaml(s, quote_sensors=False):
    """The measurements and diagnosis sections of case `s`'s study, as YAML
    lines: its measured frequencies and, where it has them, its shapes at its
    sensors (their names in double quotes with quote_sensors), and its noise."""
    lines = [
        "measurements:",
        "  - state: test",
        "    frequencies_hz: %s" % yaml_list(s["frequencies"]),
    ]
    if s["shapes"] is not None:
        sensors = ['"%s"' % x for x in s["sensors"]] if quote_sensors else s["sensors"]
        lines.append("    sensors: [%s]" % ", ".join(sensors))
        lines.append("    shapes:")
        lines += ["      - %s" % yaml_list(r) for r in s["shapes"]]
    lines += [
        "diagnosis:",
        "  noise: {frequency: %g, shape: %g}" % (s["frequency_noise"], s["shape_noise"]),
        "  use_shapes: %s" % ("true" if s["shapes"] is not None else "false"),
    ]
    return lines
