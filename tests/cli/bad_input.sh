#!/usr/bin/env bash
# Every class of bad scene input makes `rtsph run` exit with status 2 and print exactly one line
# on stderr naming the file and the JSON path at fault.
# Usage: bad_input.sh <rtsph binary> <source dir>
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" "$@"
failures=0

# check NAME FILE_ARG [FRAGMENT...]: runs the CLI on FILE_ARG, expects rc 2, one stderr line
# containing the file name and every FRAGMENT.
check() {
  local name=$1 file=$2
  shift 2
  local err lines
  runrc "$file" --steps 1 --quiet
  err=$(cat err.txt)
  lines=$(wc -l <err.txt)
  local ok=1
  [ "$rc" -eq 2 ] || { echo "FAIL $name: exit code $rc, expected 2"; ok=0; }
  [ "$lines" -eq 1 ] || { echo "FAIL $name: $lines lines on stderr, expected 1"; ok=0; }
  for fragment in "$(basename "$file")" "$@"; do
    case "$err" in
      *"$fragment"*) ;;
      *) echo "FAIL $name: stderr lacks '$fragment'"; ok=0 ;;
    esac
  done
  if [ $ok -eq 1 ]; then echo "ok   $name: $err"; else echo "     stderr: $err"; failures=$((failures + 1)); fi
}

# write NAME CONTENT: a scene file in the temp dir (printf so \x escapes make raw bytes).
write() { printf "$2" >"$work/$1"; echo "$work/$1"; }

base='"dimension": 3, "domain": {"min": [0,0,0], "max": [1,1,1]}'
block='"fluid_blocks": [{"min": [0,0,0], "max": [0.2,0.2,0.2]}]'

check missing_file "$work/no_such_scene.json" "no such file or built-in scene"
mkdir "$work/folder.json"
check unreadable "$work/folder.json" "directory"
check malformed "$(write malformed.json "{\n  $base,\n  \"fluid\": {\"spacing\": 0.02,}\n}")" "line 3, column"
check non_utf8 "$(write latin1.json "{\"name\": \"caf\xe9\"}")" "line 1" "UTF-8"
check unknown_key "$(write unknown.json "{$base, $block, \"fluid\": {\"spaceing\": 0.02}}")" "fluid.spaceing" "fluid.spacing"
check wrong_type "$(write type.json "{$base, $block, \"fluid\": {\"spacing\": \"fine\"}}")" "fluid.spacing" '"fine"'
check out_of_range "$(write range.json "{$base, $block, \"fluid\": {\"spacing\": -0.1}}")" "fluid.spacing" "-0.1"
check bad_enum "$(write enum.json "{$base, $block, \"solver\": {\"kernel\": \"spline\"}}")" "solver.kernel" '"spline"'
check array_length "$(write length.json "{\"dimension\": 2, \"domain\": {\"max\": [1, 1, 1]}}")" "domain.max" "[1,1,1]"
check min_max "$(write minmax.json "{\"domain\": {\"min\": [0,0,0], \"max\": [1,0,1]}}")" "domain.max" "[1, 0, 1]"
check block_outside "$(write outside.json "{$base, \"fluid_blocks\": [{\"min\": [0,0,0], \"max\": [2,0.5,0.5]}]}")" "fluid_blocks[0].max" "[2, 0.5, 0.5]"
check emitter_outside "$(write emitter.json "{$base, \"emitters\": [{\"position\": [0.5,5,0.5]}]}")" "emitters[0].position" "[0.5, 5, 0.5]"
check obstacle_outside "$(write obstacle.json "{$base, \"obstacles\": [{\"center\": [-1,0.5,0.5]}]}")" "obstacles[0].center" "[-1, 0.5, 0.5]"
check fixed_dt "$(write dt.json "{$base, $block, \"solver\": {\"time_step\": {\"mode\": \"fixed\", \"dt\": 0}}}")" "solver.time_step.dt" ": 0:"
check overflow "$(write overflow.json "{\n  $base,\n  \"fluid\": {\"spacing\": 1e999}\n}")" "line 3, column 24" "1e999" "number overflow"
check memory "$(write memory.json "{$base, \"fluid\": {\"spacing\": 1e-5}}")" "fluid.spacing" "1e-05" "bytes"

# A bad --set on a good scene is the same kind of error.
runrc dam_break_2d --steps 1 --quiet --set fluid.spacing=-1
if [ $rc -eq 2 ] && [ "$(wc -l <err.txt)" -eq 1 ] && grep -q -- "--set: fluid.spacing: -1" err.txt; then
  echo "ok   bad_set: $(cat err.txt)"
else
  echo "FAIL bad_set: rc $rc, stderr: $(cat err.txt)"
  failures=$((failures + 1))
fi

# Bad arguments on the command line: one readable line, the exit code, nothing run. A negative
# --until or --steps ran to the scene's end before (the default's sentinel), and CLI11's own
# range message printed the largest double to its last digit.
# one_line NAME RC FRAGMENT COMMAND...: `rtsph COMMAND...` exits RC with one short stderr line
# holding FRAGMENT and prints nothing on stdout.
one_line() {
  local name=$1 want=$2 fragment=$3
  shift 3
  set +e
  "$rtsph" "$@" >out.txt 2>err.txt
  rc=$?
  set -e
  if [ $rc -eq "$want" ] && [ "$(wc -l <err.txt)" -eq 1 ] && grep -qF -- "$fragment" err.txt \
     && [ "$(wc -c <err.txt)" -lt 200 ] && [ ! -s out.txt ]; then
    echo "ok   $name: $(cat err.txt)"
  else
    echo "FAIL $name: rc $rc (expected $want), stderr: $(cat err.txt)"
    failures=$((failures + 1))
  fi
}
one_line negative_until 2 "--until: '-1' must be zero or more (rtsph run --help lists its options)" run dam_break_2d --until -1
one_line unknown_command 2 "unknown command 'foo'; expected one of run, bench" foo
# Options that shape --export's frames are refused without it (they did nothing, silently).
one_line format_without_export 2 "--format requires --export" run dam_break_3d --until 0 --format vdb
one_line every_without_export 2 "--every requires --export" run dam_break_2d --until 0 --every 0.1
one_line negative_steps 2 "--steps: '-5' must be zero or more" run dam_break_2d --steps -5
one_line zero_every 2 "--every: '0' must be above zero" run dam_break_2d --steps 1 --every 0 --export frames
one_line word_every 2 "--every: 'abc' is not a number" run dam_break_2d --steps 1 --every abc --export frames
[ ! -e frames ] || { echo "FAIL: a refused run wrote frames"; failures=$((failures + 1)); }
# A --stats-json with no directory to go to is found before the run (with --quiet the summary
# goes only there, and it was lost after the whole run): exit 1, an I/O error.
one_line stats_json_dir 1 "no directory" run dam_break_2d --until 0.005 --quiet --stats-json "$work/no_such_dir/stats.json"
# The viewer names a bad option before it looks for a display (it said "no display" first).
if "$rtsph" view --help >/dev/null 2>&1; then  # a build with the viewer
  DISPLAY= WAYLAND_DISPLAY= one_line view_size 2 "--size 0x0: expected WxH" view dam_break_2d --size 0x0
  # A picture or video name it does not write would have become a directory of PNGs.
  one_line render_jpg 2 "--out $work/x.jpg: .jpg is not written" render dam_break_2d --out "$work/x.jpg"
fi

if [ $failures -ne 0 ]; then
  echo "$failures bad-input case(s) failed"
  exit 1
fi
echo "all bad-input cases ok"
