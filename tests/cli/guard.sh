#!/bin/bash
# Instability guard: a blow-up stops the run within the step with a diagnostic (time, step,
# particle, dt, likely cause), exit code 3 and the last good state saved; --recover halves dt
# and retries from the last good state instead, up to --max-retries times.
# Usage: guard.sh RTSPH_BINARY SOURCE_DIR
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" "$@"
unstable=(dam_break_2d --set solver.time_step.mode=fixed --set solver.time_step.dt=0.003 --threads 1)

# 1. Without --recover: exit 3, diagnostic, last good state kept.
runrc "${unstable[@]}" --until 0.3 --quiet
[ "$rc" = 3 ] || fail "unstable run: exit $rc, expected 3: $(cat err.txt)"
for want in "unstable at t = " ", step " "at particle " "dt = 0.003 s" "above the CFL limit" "c0 = "; do
  grep -q -- "$want" err.txt || fail "diagnostic lacks '$want': $(cat err.txt)"
done
grep -q "^status  *unstable" out.txt || fail "summary lacks the status: $(cat out.txt)"
# The summary describes the saved state, and says so with the time the run failed at (the
# diagnostic's): its zero time and errors read as a contradiction before.
t_fail=$(sed -n 's/.*unstable at t = \([^ ]*\) s, step.*/\1/p' err.txt)
grep -q "^status  *unstable at t = $t_fail s (the time and errors above are the last good state's" out.txt \
  || fail "summary does not give the failure's time $t_fail: $(cat out.txt)"
[ -f rtsph_unstable_dam_break_2d.ckpt ] || fail "last good state not saved: $(cat err.txt)"
"$rtsph" run --resume rtsph_unstable_dam_break_2d.ckpt --steps 0 --threads 1 --quiet >/dev/null || fail "saved state does not load"
echo "unstable: exit 3: $(head -1 err.txt)"

# 2. With a checkpoint directory, the last good state is the newest checkpoint there.
runrc "${unstable[@]}" --set solver.time_step.dt=0.0006 --until 0.3 --quiet --checkpoint-every 0.005 --checkpoint-dir ck
[ "$rc" = 3 ] || fail "exit $rc, expected 3: $(cat err.txt)"
fail_step=$(sed -n 's/.*unstable at t = [^,]*, step \([0-9]*\):.*/\1/p' err.txt)
good=$(ls ck/ckpt_*.ckpt | tail -1)
good_step=$((10#$(basename "$good" .ckpt | sed 's/ckpt_//')))
[ "$good_step" -lt "$fail_step" ] || fail "newest checkpoint (step $good_step) is not before the failure (step $fail_step)"
grep -q "last good state .* is saved in $good" err.txt || fail "kept checkpoint not named: $(cat err.txt)"
echo "unstable with checkpoints: failed at step $fail_step, last good state $good"

# 3. --recover: retries with dt halved, then completes.
runrc "${unstable[@]}" --until 0.2 --quiet --recover --snapshot-every 20 --stats-json stats.json --checkpoint-dir rk
[ "$rc" = 0 ] || fail "--recover: exit $rc: $(cat err.txt)"
grep -q "retry 1/3 from the last good state" err.txt || fail "no retry report: $(cat err.txt)"
grep -q "solver.time_step.dt 0.003 -> 0.0015 s" err.txt || fail "no dt report: $(cat err.txt)"
retries=$(python3 -c 'import json,sys; print(json.load(open("stats.json"))["retries"])' 2>/dev/null || grep -o '"retries": [0-9]*' stats.json | grep -o '[0-9]*$')
[ "$retries" -ge 1 ] || fail "stats.json retries = $retries"
# The final checkpoint carries the halved dt: resuming it continues stably.
"$rtsph" run --resume rk --until 0.25 --threads 1 --quiet >/dev/null || fail "resuming a recovered run failed"
echo "--recover: completed after $retries retries; $(grep -c 'retry' err.txt) retry lines"

# 4. --recover with too few retries gives up with exit 3.
runrc "${unstable[@]}" --until 0.2 --quiet --recover --max-retries 1
[ "$rc" = 3 ] || fail "--max-retries 1: exit $rc, expected 3: $(cat err.txt)"
grep -q "giving up after 1 retries" err.txt || fail "no give-up message: $(cat err.txt)"
echo "--recover --max-retries 1: gave up, exit 3"

# 5. The density limit is a parameter: a healthy run trips a tiny limit.
runrc dam_break_2d --until 0.2 --threads 1 --quiet --max-density-error 0.001
[ "$rc" = 3 ] && grep -q "density error .* (limit 0.1 %)" err.txt || fail "--max-density-error: exit $rc: $(cat err.txt)"
runrc dam_break_2d --until 0.05 --threads 1 --quiet
[ "$rc" = 0 ] || fail "healthy run: exit $rc: $(cat err.txt)"
echo "--max-density-error: enforced; healthy run passes"
echo "guard: all checks passed"
