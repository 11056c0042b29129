#!/usr/bin/env bash
# Campaigns in shards on batch engines (ctest, label distributed): the GNU parallel recipe (scripts/parallel-shards.sh)
# and the Slurm recipe (scripts/slurm/submit.sh, its two batch scripts run by tests/distributed/fake-slurm/sbatch,
# a stand-in that runs them here as Slurm would on a node) each give a merged report whose data is byte-identical to
# one `crankcheck validate` run: every CSV of data/, except the measured timing columns (ns_per_*) of the two timing
# tables, whose other columns must still match. Bad input stops the recipe with exit status 2 and nothing merged.
#
#   shards_test.sh CRANKCHECK SOURCE_DIR
#
# Everything happens in a fresh mkdtemp folder, removed at the end.
set -euo pipefail
crankcheck=$1
src=$2
tmp=$(mktemp -d "${TMPDIR:-/tmp}/crankcheck_test_XXXXXX")
trap 'rm -rf -- "$tmp"' EXIT
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }

# The timing tables: their ns_per_* columns are measurements (never identical from run to run); the merge keeps them
# as the shards measured them. Everything else in them is computed and must match.
timing_tables="speed_vs_error.csv integrator_pareto.csv engine_cost.csv engines.csv engines_league.csv"
drop_timings() {
  awk -F, -v OFS=, 'NR == 1 { for (i = 1; i <= NF; ++i) t[i] = ($i ~ /^ns_per_/) }
                    { s = ""; n = 0; for (i = 1; i <= NF; ++i) if (!t[i]) s = s (n++ ? OFS : "") $i; print s }' "$1"
}

# compare_data ONE MERGED: the data of a merged report against one run's.
compare_data() {
  local one=$1 merged=$2 name
  [[ -f $merged/index.md ]] || { fail "$merged: no report"; return; }
  if [[ $(cd "$one/data" && ls) != $(cd "$merged/data" && ls) ]]; then fail "$merged/data: other files than one run's"; fi
  cmp -s "$one/crankcheck-manifest.json" "$merged/crankcheck-manifest.json" || fail "$merged: another manifest"
  local count=0
  for file in "$one"/data/*.csv; do
    name=${file##*/}
    count=$((count + 1))
    if [[ " $timing_tables " == *" $name "* ]]; then
      head -n 1 "$file" | grep -q ',ns_per_' || fail "$name: no timing column"
      cmp -s <(drop_timings "$file") <(drop_timings "$merged/data/$name") || fail "$merged/data/$name: differs beyond timings"
    else
      cmp -s "$file" "$merged/data/$name" || fail "$merged/data/$name: differs from one run's"
    fi
  done
  ((count >= 15)) || fail "$one/data: only $count tables"
  echo "compared $count data files of $merged with one run's"
}

"$crankcheck" validate --quick --out "$tmp/one" >/dev/null

# GNU parallel: three shards on this machine's cores.
"$src/scripts/parallel-shards.sh" --crankcheck "$crankcheck" 3 "$tmp/parallel" -- --quick >"$tmp/parallel.log" 2>&1 ||
  { cat "$tmp/parallel.log"; fail "parallel-shards.sh: exit status $?"; }
compare_data "$tmp/one" "$tmp/parallel"
[[ $(tail -n +2 "$tmp/parallel.shards/parallel-joblog.txt" | wc -l) == 3 ]] || fail "the job log lists other than 3 shards"

# Slurm: a job array of two shards and the merge after it, through submit.sh.
PATH="$src/tests/distributed/fake-slurm:$PATH" FAKE_SLURM_STATE="$tmp/slurm-jobs" \
  "$src/scripts/slurm/submit.sh" --crankcheck "$crankcheck" --sbatch --partition=test 2 "$tmp/slurm" -- --quick \
  >"$tmp/slurm.log" 2>&1 || { cat "$tmp/slurm.log"; fail "submit.sh: exit status $?"; }
grep -q "shards: job 1000 (array 0-1); merge: job 1001" "$tmp/slurm.log" || { cat "$tmp/slurm.log"; fail "submit.sh's job ids"; }
[[ ! -e $tmp/slurm-jobs.failed ]] || { cat "$tmp/slurm-jobs.failed" "$tmp"/slurm.shards/logs/*; fail "a Slurm job failed"; }
grep -q "Shard 1/2" "$tmp/slurm.shards/logs/shard-1.out" || fail "no log of shard 1"
grep -q "All comparisons agree." "$tmp/slurm.shards/logs/merge.out" || fail "no log of the merge"
compare_data "$tmp/one" "$tmp/slurm"

# The Slurm merge refuses an incomplete set of shards, naming the missing one.
mkdir "$tmp/half"
mv "$tmp/slurm.shards/shard-1" "$tmp/half/"
status=0
bash "$src/scripts/slurm/crankcheck-merge.sbatch" "$crankcheck" 2 "$tmp/slurm.shards" "$tmp/slurm2" 2>"$tmp/merge.err" || status=$?
[[ $status == 2 && ! -e $tmp/slurm2 ]] || fail "merge of an incomplete set: exit status $status"
grep -q "shards 1 of 2 left no data" "$tmp/merge.err" || fail "merge of an incomplete set: $(cat "$tmp/merge.err")"

# Bad input: exit status 2, nothing merged.
status=0
"$src/scripts/parallel-shards.sh" --crankcheck "$crankcheck" 2 "$tmp/bad" -- --quick --no-such-flag >"$tmp/bad.log" 2>&1 ||
  status=$?
[[ $status == 2 && ! -e $tmp/bad ]] || { cat "$tmp/bad.log"; fail "a bad flag: exit status $status"; }
grep -q "shard 0/2 failed with exit status 2" "$tmp/bad.log" || { cat "$tmp/bad.log"; fail "a bad flag: no message"; }
status=0
"$src/scripts/parallel-shards.sh" --crankcheck "$crankcheck" 1 "$tmp/bad" >"$tmp/bad.log" 2>&1 || status=$?
[[ $status == 2 ]] && grep -q "N: 1: expected a number of shards from 2" "$tmp/bad.log" || fail "N = 1: exit status $status"
# A shards folder with something else in it is not used.
mkdir "$tmp/mine.shards" && touch "$tmp/mine.shards/notes.txt"
status=0
"$src/scripts/parallel-shards.sh" --crankcheck "$crankcheck" 2 "$tmp/mine" -- --quick >"$tmp/bad.log" 2>&1 || status=$?
[[ $status == 2 && -f $tmp/mine.shards/notes.txt && ! -e $tmp/mine.shards/shard-0 ]] || fail "a folder of mine: status $status"

if ((failures)); then
  echo "$failures failure(s)" >&2
  exit 1
fi
echo "all shard recipes agree with one run"
