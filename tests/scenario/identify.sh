#!/usr/bin/env bash
# femup identify: modes from measured signals.
#  1. The bundled UFF file of three measured accelerance FRFs (pyuff's free-free
#     beam, examples/data/README.md): FRF -> impulse response -> ERA with a
#     stabilisation diagram finds the six spectral peaks (52, 142, 279, 460,
#     687, 959 Hz) within 3 Hz.
#  2. A CSV free decay written here from the closed form of two damped modes
#     (10 Hz, 2 %; 25 Hz, 1 %; 1 % noise): frequencies to 0.1 %, damping to 10 %.
#  3. Bad input: a malformed CSV names file and line; nothing is written.
source "$(dirname "$0")/lib.sh"
"$FEMUP" identify "$ROOT/examples/data/pyuff_beam_frf.uff" -o out_uff -q || fail "identify uff"
[ -s out_uff/stabilisation.png ] || fail "stabilisation plot"
[ -s out_uff/identified_shapes.png ] || fail "shapes plot"
[ "$(json out_uff/modes.json "j['data']['kind']")" = frf ] || fail "frf kind"
[ "$(json out_uff/modes.json "all(any(abs(m['frequency_hz'] - p) < 3 for m in j['modes'])
  for p in (52, 142, 279, 460, 687, 959))")" = True ] || fail "beam peaks"
[ "$(json out_uff/modes.json "all(m['mpc'] > 0.9 for m in j['modes'])")" = True ] \
  || fail "mpc"

/usr/bin/env python3 - <<'PY'
import math, random
random.seed(7)
fs, n = 200.0, 800
modes = [(10.0, 0.02, (0.5, 1.0)), (25.0, 0.01, (1.0, -0.6))]
rows = []
for k in range(n):
    t = k / fs
    row = []
    for ch in range(2):
        v = 0.0
        for f, z, shape in modes:
            w = 2 * math.pi * f
            wd = w * math.sqrt(1 - z * z)
            v += shape[ch] * math.exp(-z * w * t) * math.cos(wd * t)
        row.append(v)
    rows.append((t, row))
rms = [math.sqrt(sum(r[1][c] ** 2 for r in rows) / n) for c in range(2)]
with open("decay.csv", "w") as out:
    out.write("time,a1,a2\n")
    for t, row in rows:
        out.write("%.6f,%s\n" % (t, ",".join("%.9e" % (v + 0.01 * rms[c] * random.gauss(0, 1))
                                             for c, v in enumerate(row))))
PY
"$FEMUP" identify decay.csv --first-sample 0 --max-order 20 -o out_csv -q || fail "identify csv"
[ "$(json out_csv/modes.json "len(j['modes'])")" = 2 ] || fail "two modes"
[ "$(json out_csv/modes.json "abs(j['modes'][0]['frequency_hz'] - 10) < 0.01
  and abs(j['modes'][1]['frequency_hz'] - 25) < 0.025")" = True ] || fail "frequencies"
[ "$(json out_csv/modes.json "abs(j['modes'][0]['damping_ratio'] - 0.02) < 0.002
  and abs(j['modes'][1]['damping_ratio'] - 0.01) < 0.001")" = True ] || fail "damping"

printf 'time,a1\n0,1\n0.005,x\n' > bad.csv
"$FEMUP" identify bad.csv -o out_bad 2> err.txt && fail "bad csv accepted"
grep -q "bad.csv" err.txt && grep -q "line 3" err.txt || fail "message: $(cat err.txt)"
[ ! -e out_bad/modes.json ] || fail "partial output"
"$FEMUP" identify nothing.wav -o out_none 2> err2.txt && fail "unknown format accepted"
grep -q "extension" err2.txt || fail "format message"
echo "identify: ok"
