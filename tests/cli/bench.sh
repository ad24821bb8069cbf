#!/bin/bash
# `rtsph bench --method M` and `rtsph bench --realtime`: each method's table, the capacity search
# (structure and consistency only; speed is measured in benchmarks, never asserted) and bad
# input.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" "$@"

for m in wcsph pbf dfsph; do
  "$rtsph" bench --dim 2 --method $m --particles 500 --steps 3 --json b_$m.json >out.txt
  grep -q "2D dam break, $m" out.txt || fail "bench --method $m: header does not name the method"
  python3 - "$m" <<'PY' || fail "bench --method $m: bad JSON"
import json, sys
j = json.load(open(f"b_{sys.argv[1]}.json"))
assert j["method"] == sys.argv[1] and len(j["rows"]) == 1
assert j["rows"][0]["fluid_particles"] > 0 and j["rows"][0]["fluid_particle_steps_per_s"] > 0
PY
done

# A tiny window keeps this short; the answer is whichever probe kept up (or none).
"$rtsph" bench --realtime --dim 2 --method dfsph --window 0.05 --json rt.json >out.txt
grep -q "^real-time capacity: " out.txt || fail "bench --realtime printed no answer"
python3 - <<'PY' || fail "bench --realtime: JSON inconsistent with its probes"
import json
j = json.load(open("rt.json"))
assert j["method"] == "dfsph" and j["dimension"] == 2 and j["probes"]
fast = [p["fluid_particles"] for p in j["probes"] if p["real_time_factor"] >= 1]
assert j["capacity_fluid_particles"] == (max(fast) if fast else 0), j
for p in j["probes"]:
    assert p["steps"] > 0 and p["sim_s"] > 0 and p["wall_s"] > 0
PY

# --set is applied to the benched scene (a bad value is refused below) and the JSON records it.
"$rtsph" bench --dim 2 --method pbf --particles 500 --steps 3 --set solver.pbf.substeps=1 --json s.json >/dev/null
python3 - <<'PY' || fail "bench --set: not recorded in the JSON"
import json
j = json.load(open("s.json"))
assert j["set"] == ["solver.pbf.substeps=1"], j
PY

# Bad input: one line, exit 2.
for args in "--set fluid.spacing=0.1" "--set solver.method=pbf" "--set solver.pbf.substeps=0" "--set nope=1" \
            "--gravity tree --set solver.pbf.substeps=2"; do
  set +e
  "$rtsph" bench --particles 500 --steps 1 $args 2>err.txt >out.txt
  rc=$?
  set -e
  [ $rc -eq 2 ] || fail "bench $args exited $rc, expected 2"
  [ "$(wc -l <err.txt)" -eq 1 ] || { cat err.txt; fail "bench $args: expected one line"; }
  [ ! -s out.txt ] || { cat out.txt; fail "bench $args: printed a table before refusing"; }
done
set +e
"$rtsph" bench --method nope 2>err.txt >/dev/null
rc=$?
set -e
[ $rc -ne 0 ] || fail "bench --method nope exited 0"
[ "$(wc -l <err.txt)" -eq 1 ] || { cat err.txt; fail "bench --method nope: expected one line"; }
# A --json that cannot be written is refused before the runs (it failed after them).
set +e
"$rtsph" bench --particles 500 --steps 1 --json no_such_dir/b.json 2>err.txt >out.txt
rc=$?
set -e
[ $rc -eq 1 ] || fail "bench --json no_such_dir/b.json exited $rc, expected 1"
grep -q "no directory" err.txt || { cat err.txt; fail "bench --json: no 'no directory' in the message"; }
[ ! -s out.txt ] || { cat out.txt; fail "bench --json: ran before refusing"; }
echo "bench test passed"
