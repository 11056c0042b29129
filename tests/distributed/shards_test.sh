#!/usr/bin/env bash
# Campaigns in shards on batch engines (ctest, label distributed): the GNU parallel recipe (scripts/parallel-shards.sh)
# and the Slurm recipe (scripts/slurm/submit.sh and its two batch scripts, on a real one-node Slurm cluster that this
# test starts here: munged, slurmctld and slurmd from Debian's packages, on 127.0.0.1) each give a merged report whose
# data is byte-identical to one `crankcheck validate --quick SCENE` run: every CSV of data/, except the measured timing
# columns (ns_per_*) of the timing tables, whose other columns must still match. On Slurm, a shard that fails (a bad
# scene) or is cancelled (scancel) makes the merge job refuse, naming the shard; a job sbatch refuses is not left
# submitted. Bad input stops the recipes with exit status 2 and nothing merged; so does a shard changed after it was
# written. What a user gives reaches crankcheck as it is, on both engines (issue 46): scenes, OUT and the working
# folder with {}, {= ... =}, %, a backslash, quotes, a newline or a leading -, relative scenes and a `--` in
# VALIDATE-ARGS; and what the recipes cannot give every shard (--profile, --out, --shard; on Slurm also --sbatch
# words that are not options or set its own options) is refused up front: exit status 2, one line, nothing run,
# submitted or created.
#
#   shards_test.sh CRANKCHECK SOURCE_DIR [ONE]
#
# ONE: that one run's report, already written (under ctest the fixture one_scene_campaign's, `validate --quick SCENE
# --jobs 1`, which ValidateTest.ShardsMergeIntoTheSameReportAsOneRun compares with too: run once for both, issue 28);
# without it the test runs it here.
# The Slurm part needs root and Debian's slurmctld, slurmd, munge and slurm-client (scripts/setup.sh installs them);
# without them the test runs the GNU parallel part, then says why and exits 77, which ctest reports as skipped.
# Everything happens in a fresh mktemp folder: the cluster's configuration, munge key and socket, state, spool, logs
# and pid files, and every report. When the test ends, also on a failure or a signal, the jobs it submitted are
# cancelled, the three daemons it started are stopped by their process ids, and the folder is removed.
set -euo pipefail
crankcheck=$1
src=$2
one=${3:+$(realpath -- "$3")}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/crankcheck_test_XXXXXX")
daemons=()  # "name pid" of each daemon started here, in the order they started
relative_jobs=() percent_jobs=()
submitted=()  # the Slurm jobs submitted here

stop_cluster() {
  local i k name pid
  if ((${#submitted[@]})) && [[ -n ${SLURM_CONF:-} ]]; then
    scancel "${submitted[@]}" 2>/dev/null || true
    for ((i = 0; i < 100; ++i)); do  # up to 20 s for their processes to end
      scontrol -o show job 2>/dev/null | grep -Eq 'JobState=(RUNNING|COMPLETING|CONFIGURING|SUSPENDED)' || break
      sleep 0.2
    done
  fi
  for ((k = ${#daemons[@]} - 1; k >= 0; --k)); do  # slurmd, slurmctld, then munged
    read -r name pid <<<"${daemons[k]}"
    kill -TERM "$pid" 2>/dev/null || continue
    for ((i = 0; i < 100; ++i)); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    if kill -0 "$pid" 2>/dev/null; then
      echo "$name (pid $pid) ignored SIGTERM for 10 s: killed" >&2
      kill -KILL "$pid" 2>/dev/null || true
    fi
    wait "$pid" 2>/dev/null || true
  done
}
cleanup() {
  stop_cluster
  rm -rf -- "$tmp"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }

# Can this machine run the Slurm part? Said now; the GNU parallel part runs either way.
skip=""
if (($(id -u) != 0)); then
  skip="not root (uid $(id -u)): the one-node Slurm cluster runs munged, slurmctld and slurmd as root (SlurmUser=root)"
else
  missing=()
  for program in munged munge slurmctld slurmd sbatch scontrol scancel; do
    command -v "$program" >/dev/null || missing+=("$program")
  done
  if ((${#missing[@]})); then
    skip="no ${missing[*]} on PATH (Debian: apt-get install slurmctld slurmd munge slurm-client; scripts/setup.sh does)"
  fi
fi
[[ -z $skip ]] || echo "SKIP (the Slurm part): $skip"

# The timing tables: their ns_per_* and seconds columns are measurements (never identical from run to run); the merge keeps them
# as the shards measured them. Everything else in them is computed and must match.
timing_tables="speed_vs_error.csv integrator_pareto.csv engine_cost.csv engines.csv engines_league.csv torsion_cost.csv stepped_cost.csv"
drop_timings() {
  awk -F, -v OFS=, 'NR == 1 { for (i = 1; i <= NF; ++i) t[i] = ($i ~ /^(ns_per_|seconds)/) }
                    { s = ""; n = 0; for (i = 1; i <= NF; ++i) if (!t[i]) s = s (n++ ? OFS : "") $i; print s }' "$1"
}

# manifest_paths FOLDER: the files its crankcheck-manifest.json lists, one per line.
manifest_paths() {
  python3 -c 'import json, sys; print("\n".join(f["path"] for f in json.load(open(sys.argv[1]))["files"]))' \
    "$1/crankcheck-manifest.json"
}

# compare_data ONE MERGED: the data of a merged report against one run's.
compare_data() {
  local one=$1 merged=$2 name
  [[ -f $merged/index.md ]] || { fail "$merged: no report"; return; }
  if [[ $(cd "$one/data" && ls) != $(cd "$merged/data" && ls) ]]; then fail "$merged/data: other files than one run's"; fi
  # The same files listed (their sizes and checksums differ where a timing column does).
  cmp -s <(manifest_paths "$one") <(manifest_paths "$merged") || fail "$merged: its manifest lists other files"
  local count=0
  for file in "$one"/data/*.csv; do
    name=${file##*/}
    count=$((count + 1))
    if [[ " $timing_tables " == *" $name "* ]]; then
      head -n 1 "$file" | grep -qE ',(ns_per_|seconds)' || fail "$name: no timing column"
      cmp -s <(drop_timings "$file") <(drop_timings "$merged/data/$name") || fail "$merged/data/$name: differs beyond timings"
    else
      cmp -s "$file" "$merged/data/$name" || fail "$merged/data/$name: differs from one run's"
    fi
  done
  ((count >= 15)) || fail "$one/data: only $count tables"
  echo "compared $count data files of $merged with one run's"
}

# The campaign: one example scene, --quick (every part and table; the default campaign's many families shard by the
# same rule and take several times as long).
campaign_scene="$src/scenes/inline4_four_stroke.toml"
if [[ -n $one ]]; then
  [[ -f $one/index.md && -f $one/crankcheck-manifest.json ]] || { echo "FAIL: $one: not a report (the one run)" >&2; exit 1; }
else
  one=$tmp/one
  "$crankcheck" validate --quick "$campaign_scene" --out "$one" >/dev/null
fi

# GNU parallel: three shards on this machine's cores.
"$src/scripts/parallel-shards.sh" --crankcheck "$crankcheck" 3 "$tmp/parallel" -- --quick "$campaign_scene" \
    >"$tmp/parallel.log" 2>&1 ||
  { cat "$tmp/parallel.log"; fail "parallel-shards.sh: exit status $?"; }
compare_data "$one" "$tmp/parallel"
[[ $(tail -n +2 "$tmp/parallel.shards/parallel-joblog.txt" | wc -l) == 3 ]] || fail "the job log lists other than 3 shards"
# A shard changed after it was written (a data file's last line gone): the merge refuses, naming the file.
cp -r "$tmp/parallel.shards" "$tmp/changed.shards"
changed=$(cd "$tmp/changed.shards/shard-1/data" && ls | head -n 1)
sed -i '$d' "$tmp/changed.shards/shard-1/data/$changed"
status=0
"$crankcheck" report merge "$tmp"/changed.shards/shard-{0,1,2} --out "$tmp/changed" >/dev/null 2>"$tmp/changed.log" ||
  status=$?
[[ $status == 2 && ! -e $tmp/changed ]] &&
  grep -q "^crankcheck: report merge: \"$tmp/changed.shards/shard-1/data/$changed\": " "$tmp/changed.log" ||
  fail "a changed shard: exit status $status: $(cat "$tmp/changed.log")"

# Bad input: exit status 2, nothing merged.
status=0
"$src/scripts/parallel-shards.sh" --crankcheck "$crankcheck" 2 "$tmp/bad" -- --quick --no-such-flag >"$tmp/bad.log" 2>&1 ||
  status=$?
# Found by `validate --check` before any shard runs: crankcheck's own line, no shards folder made.
[[ $status == 2 && ! -e $tmp/bad && ! -e $tmp/bad.shards ]] || { cat "$tmp/bad.log"; fail "a bad flag: exit status $status"; }
grep -q "crankcheck: --no-such-flag: unknown flag" "$tmp/bad.log" || { cat "$tmp/bad.log"; fail "a bad flag: no message"; }
# OUT a folder of the user's: refused by crankcheck's rule before any shard runs (every shard once ran, then the
# merge refused it), the folder as it was, no shards folder made.
mkdir "$tmp/myout" && echo mine >"$tmp/myout/notes.txt"
status=0
"$src/scripts/parallel-shards.sh" --crankcheck "$crankcheck" 2 "$tmp/myout" -- --quick >"$tmp/bad.log" 2>&1 || status=$?
[[ $status == 2 && $(cat "$tmp/myout/notes.txt") == mine && ! -e $tmp/myout.shards ]] &&
  grep -q 'holds "notes.txt", which crankcheck did not write' "$tmp/bad.log" ||
  { cat "$tmp/bad.log"; fail "OUT a folder of mine: status $status"; }
status=0
"$src/scripts/parallel-shards.sh" --crankcheck "$crankcheck" 1 "$tmp/bad" >"$tmp/bad.log" 2>&1 || status=$?
[[ $status == 2 ]] && grep -q "N: 1: expected a number of shards from 2" "$tmp/bad.log" || fail "N = 1: exit status $status"
# A shards folder with something else in it is not used.
mkdir "$tmp/mine.shards" && touch "$tmp/mine.shards/notes.txt"
status=0
"$src/scripts/parallel-shards.sh" --crankcheck "$crankcheck" 2 "$tmp/mine" -- --quick >"$tmp/bad.log" 2>&1 || status=$?
[[ $status == 2 && -f $tmp/mine.shards/notes.txt && ! -e $tmp/mine.shards/shard-0 ]] || fail "a folder of mine: status $status"

# Hostile names (issue 46): a scene or OUT with {}, {= ... =}, quotes, a newline or a leading - reaches crankcheck as
# it is, never as GNU parallel's template nor as Perl (a scene x{=system(...)=}.toml once created PWNED; a{}b.toml
# once became a0b.toml). Relative scenes, from a folder whose own name is hostile; one part (pin_load_polar, 0.1 s).
hostile=$tmp/$'h{}{1}{.}%\\ \'" :::\nd'
mkdir "$hostile"
scene_perl='x{=system(q(touch),q(PWNED))=}.toml' scene_braces='a{}b.toml'
cp "$src/scenes/single_cylinder.toml" "$hostile/$scene_perl"
cp "$src/scenes/single_cylinder.toml" "$hostile/$scene_braces"
cp "$src/scenes/single_cylinder.toml" "$hostile/-dash.toml"
hostile_out='o{} {=system(q(touch),q(PWNED))=} :::'
status=0
(cd "$hostile" && "$src/scripts/parallel-shards.sh" --crankcheck "$crankcheck" 2 "$hostile_out" -- --quick --parts pin_load_polar \
  "$scene_perl" "$scene_braces") >"$tmp/hostile.log" 2>&1 || status=$?
[[ $status == 0 && -f $hostile/$hostile_out/index.md ]] || { cat "$tmp/hostile.log"; fail "hostile names: exit status $status"; }
[[ -z $(find "$tmp" -name PWNED) ]] || fail "hostile names: a scene's name ran as Perl (PWNED)"
grep -q "^a{}b," "$hostile/$hostile_out/data/scenes.csv" 2>/dev/null &&
  grep -qF "\"${scene_perl%.toml}\"," "$hostile/$hostile_out/data/scenes.csv" ||
  fail "hostile names: the merged report's scenes: $(cat "$hostile/$hostile_out/data/scenes.csv" 2>&1)"
# N with a leading zero is decimal (010 was octal 8: 8 shards of "/010", and the merge refused); a `--` in
# VALIDATE-ARGS, then a scene whose name starts with -, is theirs (the script's --shard and --out once came after
# it, as scenes). In the CSV the name is '-dash: a text cell that begins with - is written guarded against a
# spreadsheet's formulas (reports/README.md).
status=0
(cd "$hostile" && "$src/scripts/parallel-shards.sh" --crankcheck "$crankcheck" 010 "$tmp/decimal" -- --quick \
  --parts pin_load_polar -- -dash.toml) >"$tmp/decimal.log" 2>&1 || status=$?
[[ $status == 0 && $(tail -n +2 "$tmp/decimal.shards/parallel-joblog.txt" | wc -l) == 10 ]] &&
  grep -q "^'-dash," "$tmp/decimal/data/scenes.csv" || { cat "$tmp/decimal.log"; fail "N = 010 and -- -dash.toml: exit status $status"; }

# VALIDATE-ARGS the script cannot pass to every shard, and arguments it cannot use: exit status 2 and one line
# naming the flag, before anything is created or run (--profile once ran every shard, then failed with 3).
refused_up_front() {  # refused_up_front WHAT MESSAGE ARGS...: parallel-shards.sh ARGS (OUT $tmp/upfront) refuses so
  local what=$1 message=$2 status=0
  shift 2
  rm -rf -- "$tmp/upfront" "$tmp/upfront.shards"  # what an earlier case left (a failure, said there)
  "$src/scripts/parallel-shards.sh" --crankcheck "$crankcheck" "$@" >"$tmp/upfront.log" 2>&1 || status=$?
  [[ $status == 2 && $(wc -l <"$tmp/upfront.log") == 1 && ! -e $tmp/upfront && ! -e $tmp/upfront.shards ]] &&
    grep -qF -- "$message" "$tmp/upfront.log" || { cat "$tmp/upfront.log"; fail "$what: exit status $status"; }
}
refused_up_front "--profile" "VALIDATE-ARGS: --profile: every shard would write the one FILE" \
  2 "$tmp/upfront" -- --quick "$campaign_scene" --profile "$tmp/profile.csv"
[[ ! -e $tmp/profile.csv ]] || fail "--profile: written"
refused_up_front "--profile=FILE" "VALIDATE-ARGS: --profile:" 2 "$tmp/upfront" -- --quick --profile="$tmp/profile.csv"
refused_up_front "--out" "VALIDATE-ARGS: --out:" 2 "$tmp/upfront" -- --quick --out "$tmp/elsewhere"
refused_up_front "--shard" "VALIDATE-ARGS: --shard:" 2 "$tmp/upfront" -- --quick --shard=0/2
refused_up_front "--help" "VALIDATE-ARGS: --help:" 2 "$tmp/upfront" -- --help
refused_up_front "N = 100001" "N: 100001: expected a number of shards from 2" 100001 "$tmp/upfront"
refused_up_front "an empty OUT" "OUT: empty" 2 ""
refused_up_front "an empty --shards" "--shards: empty" --shards "" 2 "$tmp/upfront"
refused_up_front "--shards OUT" "the same folder as OUT" --shards "$tmp/upfront" 2 "$tmp/upfront"
refused_up_front "OUT in --shards" "one inside the other" --shards "$tmp/upfront.shards" 2 "$tmp/upfront.shards/report"

if [[ -n $skip ]]; then
  if ((failures)); then
    echo "$failures failure(s)" >&2
    exit 1
  fi
  echo "GNU parallel's recipe agrees with one run; the Slurm part is skipped: $skip"
  exit 77
fi

# ---- A one-node Slurm cluster in $tmp/slurm-cluster -------------------------------------------------------------
# Nothing of the machine's own Slurm or munge is used: the configuration, key, socket, state and logs are all here,
# and the two Slurm ports are free ones on 127.0.0.1.
unset "${!SLURM_@}" "${!SBATCH_@}"  # a Slurm job's or the user's settings would change what sbatch does
cluster=$tmp/slurm-cluster
mkdir -p "$cluster/state" "$cluster/spool"
chmod 711 "$tmp"  # munged wants every folder above its socket searchable by all (not readable)
cd "$tmp"         # the daemons' and the jobs' working folder (sbatch's default)

show_logs() {  # show_logs: the daemons' last words, when the cluster does not come up
  local file
  for file in "$cluster"/*.out "$cluster"/*.log; do
    [[ -f $file ]] && { echo "--- $file" >&2; tail -n 20 "$file" >&2; }
  done
}
die() {  # die MESSAGE: the cluster cannot be used; the rest of the Slurm part would only fail the same way
  fail "$*"
  show_logs
  echo "$failures failure(s)" >&2
  exit 1
}
# await SECONDS WHAT COMMAND...: runs COMMAND every 0.2 s until it succeeds; fails the test after SECONDS, or when
# the Slurm part has used its 150 s (so that the test ends, and cleans up, well within ctest's TIMEOUT).
deadline=$((SECONDS + 150))
await() {
  local seconds=$1 what=$2 end=$((SECONDS + $1))
  shift 2
  ((end < deadline)) || end=$deadline
  until "$@"; do
    ((SECONDS < end)) || { fail "$what: not within $seconds s (or the Slurm part's 150 s)"; return 1; }
    sleep 0.2
  done
}
free_port() {  # free_port NOT: a TCP port nothing listens on at 127.0.0.1, other than NOT
  local port
  while :; do
    port=$((20000 + RANDOM % 30000))
    [[ $port != "${1:-}" ]] && ! (: <>"/dev/tcp/127.0.0.1/$port") 2>/dev/null && break
  done
  echo "$port"
}
running() { kill -0 "$1" 2>/dev/null; }

head -c 1024 /dev/urandom >"$cluster/munge.key"
chmod 400 "$cluster/munge.key"
munged --foreground --key-file="$cluster/munge.key" --socket="$cluster/munge.socket" \
  --pid-file="$cluster/munged.pid" --log-file="$cluster/munged.log" --seed-file="$cluster/munged.seed" \
  >"$cluster/munged.out" 2>&1 &
daemons+=("munged $!")
munge_works() {  # a credential made and decoded through the socket
  munge --socket="$cluster/munge.socket" --no-input 2>/dev/null | unmunge --socket="$cluster/munge.socket" >/dev/null 2>&1
}
await 20 "munged's socket $cluster/munge.socket" munge_works || die "munged did not start"

host=$(hostname -s)
node=$(slurmd -C | head -n 1)  # this machine as slurmd sees it: NodeName=HOST CPUs=... RealMemory=...
[[ $node == "NodeName=$host "*RealMemory=* ]] || die "slurmd -C: unexpected: $node"
ctld_port=$(free_port)
slurmd_port=$(free_port "$ctld_port")
cat >"$cluster/slurm.conf" <<EOF
# A one-node cluster for tests/distributed/shards_test.sh: everything in $cluster.
ClusterName=crankcheck-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$cluster/munge.socket
StateSaveLocation=$cluster/state
SlurmdSpoolDir=$cluster/spool
SlurmctldPidFile=$cluster/slurmctld.pid
SlurmdPidFile=$cluster/slurmd.pid
SlurmctldLogFile=$cluster/slurmctld.log
SlurmdLogFile=$cluster/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
MailProg=/bin/true
# Jobs scheduled when they are submitted, released or freed by a dependency (Slurm's default lets a busy cluster put
# it off by up to 3 s a time; here it was 5-9 s of the test's waiting, issue 28).
SchedulerParameters=batch_sched_delay=0
$node NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=crankcheck Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$cluster/slurm.conf
slurmctld -D -i >"$cluster/slurmctld.out" 2>&1 &
daemons+=("slurmctld $!")
ctld_up() { running "${daemons[1]#* }" && scontrol ping 2>/dev/null | grep -q "is UP"; }
await 30 "slurmctld on port $ctld_port" ctld_up || die "slurmctld did not start"
slurmd -D -N "$host" >"$cluster/slurmd.out" 2>&1 &
daemons+=("slurmd $!")
node_idle() { running "${daemons[2]#* }" && scontrol -o show node "$host" 2>/dev/null | grep -q "State=IDLE "; }
await 30 "slurmd: node $host idle" node_idle || die "slurmd did not start"
echo "a one-node Slurm cluster: ${daemons[*]}; ${node%% RealMemory*} on $host, ports $ctld_port and $slurmd_port"

# submit ARGS...: scripts/slurm/submit.sh ARGS; sets array_job and merge_job from what it prints.
submit() { submit_with "$crankcheck" "$@"; }
# submit_with CRANKCHECK ARGS...: submit, with that crankcheck program.
submit_with() {
  local log=$tmp/submit-${#submitted[@]}.log program=$1
  shift
  array_job="" merge_job=""
  "$src/scripts/slurm/submit.sh" --crankcheck "$program" --sbatch --partition=crankcheck "$@" >"$log" 2>&1 ||
    { cat "$log"; fail "submit.sh $*: exit status $?"; return 1; }
  [[ $(cat "$log") =~ shards:\ job\ ([0-9]+)\ \(array\ 0-[0-9]+\)\;\ merge:\ job\ ([0-9]+) ]] ||
    { cat "$log"; fail "submit.sh $*: no job ids"; return 1; }
  array_job=${BASH_REMATCH[1]} merge_job=${BASH_REMATCH[2]}
  submitted+=("$array_job" "$merge_job")
}
# field JOB NAME: NAME's value in `scontrol show job JOB` (JOB may be ARRAY_TASK); "" if it has none.
field() { scontrol -o show job "$1" 2>/dev/null | grep -o "\(^\| \)$2=[^ ]*" | head -n 1 | cut -d= -f2- || true; }
ended() {  # ended JOB...: every record of each JOB (every task of an array) has reached a final state
  local job state
  for job; do
    state=$(scontrol -o show job "$job" 2>/dev/null | grep -o ' JobState=[A-Z_]*' | sort -u) || return 1
    [[ -n $state ]] || return 1
    ! grep -qvE 'JobState=(COMPLETED|FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY|PREEMPTED|BOOT_FAIL|DEADLINE)$' \
      <<<"$state" || return 1
  done
}
# expect JOB STATE EXITCODE: the job ended so (EXITCODE "" for any).
expect() {
  local state exit_code
  state=$(field "$1" JobState) exit_code=$(field "$1" ExitCode)
  [[ $state == "$2" && ( -z $3 || $exit_code == "$3" ) ]] ||
    fail "job $1: $state, exit code $exit_code; expected $2${3:+, exit code $3}"
}

# 1. A job array of two shards and the merge after it, through submit.sh; the merged data is one run's.
if submit 2 "$tmp/slurm" -- --quick "$campaign_scene" && await 90 "jobs $array_job and $merge_job" ended "$array_job" "$merge_job"; then
  before=$failures
  expect "${array_job}_0" COMPLETED 0:0
  expect "${array_job}_1" COMPLETED 0:0
  expect "$merge_job" COMPLETED 0:0
  if ((failures > before)); then
    for file in "$tmp"/slurm.shards/logs/* "$cluster/slurmd.log"; do echo "--- $file" >&2; tail -n 20 "$file" >&2; done
  fi
  # What the scripts ask of Slurm: their #SBATCH defaults, and submit.sh's --sbatch option for both jobs.
  [[ $(field "${array_job}_1" CPUs/Task) == 1 && $(field "${array_job}_1" TimeLimit) == 02:00:00 ]] ||
    fail "the shards' #SBATCH defaults: $(field "${array_job}_1" CPUs/Task) CPU, $(field "${array_job}_1" TimeLimit)"
  [[ $(field "$merge_job" TimeLimit) == 00:30:00 && $(field "$merge_job" Partition) == crankcheck ]] ||
    fail "the merge's time limit and partition: $(field "$merge_job" TimeLimit), $(field "$merge_job" Partition)"
  grep -q "Shard 0/2" "$tmp/slurm.shards/logs/shard-0.out" || fail "no log of shard 0"
  grep -q "Shard 1/2" "$tmp/slurm.shards/logs/shard-1.out" || fail "no log of shard 1"
  grep -q "^100% of comparisons agree, 0 failed out of " "$tmp/slurm.shards/logs/merge.out" || fail "no log of the merge"
  compare_data "$one" "$tmp/slurm"
fi

# refused_merge OUT SHARDS...: the merge job ended with exit code 2, naming exactly SHARDS, and wrote no OUT.
refused_merge() {
  local out=$1 log=$1.shards/logs/merge.out
  shift
  expect "$merge_job" FAILED 2:0
  grep -q "shards $* of 2 left no data" "$log" || { cat "$log"; fail "$out: the merge does not name shards $*"; }
  [[ ! -e $out ]] || fail "$out: merged, though shards $* are missing"
}

# 2. A failing shard: the scene is broken after task 0 ran and before task 1 runs (both held until then). One part
# (--parts pin_load_polar, 0.1 s; the whole quick campaign of the scene took 3 s): what is checked is how the shard
# fails and what the merge says, not the shard's data (compared in 1).
scene=$tmp/scene.toml
cp "$src/scenes/single_cylinder.toml" "$scene"
if submit --sbatch --hold 2 "$tmp/badscene" -- --quick --parts pin_load_polar "$scene"; then
  [[ $(field "$merge_job" Dependency) == "afterany:${array_job}_*(unfulfilled)" ]] ||
    fail "the merge's dependency: $(field "$merge_job" Dependency)"
  scontrol release "${array_job}_0"
  if await 60 "task ${array_job}_0" ended "${array_job}_0"; then
    expect "${array_job}_0" COMPLETED 0:0
    echo "cylinders = [" >>"$scene"
    scontrol release "${array_job}_1"
    scontrol release "$merge_job"
    if await 60 "jobs $array_job and $merge_job" ended "$array_job" "$merge_job"; then
      expect "${array_job}_1" FAILED 2:0
      grep -q "crankcheck: $scene: .*not valid TOML" "$tmp/badscene.shards/logs/shard-1.out" ||
        fail "shard 1's log does not name the bad scene: $(cat "$tmp/badscene.shards/logs/shard-1.out")"
      refused_merge "$tmp/badscene" 1
      grep -q "shard 1: .*shard-1.out: crankcheck: $scene" "$tmp/badscene.shards/logs/merge.out" ||
        fail "the merge does not say why shard 1 failed: $(cat "$tmp/badscene.shards/logs/merge.out")"
    fi
  fi
fi

# 3. Cancelled tasks: task 0 while it waits, task 1 while it runs. Task 1 is held at a barrier until it is cancelled,
# whatever the work would take (a shard that finished first used to leave data and fail the test, issue 58): the
# crankcheck the recipe is given here is a wrapper that, for a shard, marks that it started and then waits (120 s at
# most, then fails the shard: a test never waits without a limit); the merge goes to the real crankcheck.
held=$tmp/held-crankcheck
cat >"$held" <<EOF
#!/usr/bin/env bash
if [[ \$1 == validate && \$2 != --check ]]; then  # submit.sh's own check before it submits goes through
  touch "$tmp/held.started"
  sleep 120
  echo "held-crankcheck: not cancelled within 120 s" >&2
  exit 1
fi
exec "$crankcheck" "\$@"
EOF
chmod +x "$held"
at_barrier() { [[ -e $tmp/held.started ]]; }
if submit_with "$held" --sbatch --hold 2 "$tmp/cancelled" -- --quick "$campaign_scene"; then
  scancel "${array_job}_0"
  scontrol release "${array_job}_1"
  if await 60 "task ${array_job}_1 at its barrier" at_barrier; then
    scancel "${array_job}_1"
    scontrol release "$merge_job"
    if await 60 "jobs $array_job and $merge_job" ended "$array_job" "$merge_job"; then
      expect "${array_job}_1" CANCELLED ""
      grep -q "\*\*\* JOB [0-9]* ON $host CANCELLED AT" "$tmp/cancelled.shards/logs/shard-1.out" ||
        fail "no cancellation in shard 1's log: $(cat "$tmp/cancelled.shards/logs/shard-1.out")"
      [[ ! -e $tmp/cancelled.shards/shard-1/shard.json ]] || fail "the cancelled shard 1 left data"
      refused_merge "$tmp/cancelled" 0 1
      grep -q "shard 0: no log .*never started" "$tmp/cancelled.shards/logs/merge.out" &&
        grep -q "shard 1: .*CANCELLED AT" "$tmp/cancelled.shards/logs/merge.out" ||
        fail "the merge does not say why shards 0 and 1 are missing: $(cat "$tmp/cancelled.shards/logs/merge.out")"
    fi
  fi
fi

# 4. A job sbatch refuses: exit status 2 with Slurm's reason, nothing left submitted, no folders left behind.
records=$(scontrol -o show job | wc -l)
status=0
"$src/scripts/slurm/submit.sh" --crankcheck "$crankcheck" --sbatch --partition=no-such-partition 2 \
  "$tmp/refused/report" -- --quick >"$tmp/refused.log" 2>&1 || status=$?
[[ $status == 2 && ! -e $tmp/refused ]] || { cat "$tmp/refused.log"; fail "a refused job: exit status $status"; }
grep -q "sbatch: error: .*[Ii]nvalid partition" "$tmp/refused.log" &&
  grep -q "submit.sh: sbatch refused the shards' job array .*nothing submitted" "$tmp/refused.log" ||
  fail "a refused job: $(cat "$tmp/refused.log")"
[[ $(scontrol -o show job | wc -l) == "$records" ]] || fail "a refused job: submitted all the same"

# 5. What a user gives reaches the jobs as it is (issue 46). a) Relative scene paths, run in the submitting folder
# (sbatch --chdir; its name has %, a backslash, braces, quotes and a newline): submit.sh once made every argument
# naming a file absolute, so in a folder holding a file `offset`, --parts offset became --parts /.../offset and every
# shard failed. b) An OUT with % (sbatch's filename patterns): out%j once gave each job a log folder that did not
# exist (JobLaunchFailure, no log, submit.sh exit status 0). One part each (0.1 s); both submitted, then awaited.
workdir=$tmp/$'w%j\\b%%x {} \' "\nd'
mkdir "$workdir"
cp "$src/scenes/single_cylinder.toml" "$workdir/scene.toml"
touch "$workdir/offset"
percent=$tmp/$'pct%j%a%%x %N'
cd "$workdir"
submit 2 "$tmp/relative" -- --quick --parts offset scene.toml && relative_jobs=("$array_job" "$merge_job")
cd "$tmp"
submit 2 "$percent" -- --quick --parts offset "$workdir/scene.toml" && percent_jobs=("$array_job" "$merge_job")
if ((${#relative_jobs[@]})) && await 60 "jobs ${relative_jobs[*]}" ended "${relative_jobs[@]}"; then
  expect "${relative_jobs[0]}_0" COMPLETED 0:0
  expect "${relative_jobs[0]}_1" COMPLETED 0:0
  expect "${relative_jobs[1]}" COMPLETED 0:0
  grep -q "^scene," "$tmp/relative/data/scenes.csv" 2>/dev/null && [[ -f $tmp/relative/offset.svg ]] ||
    fail "relative paths: no merged report of scene.toml: $(cat "$tmp"/relative.shards/logs/*.out 2>&1)"
fi
if ((${#percent_jobs[@]})) && await 60 "jobs ${percent_jobs[*]}" ended "${percent_jobs[@]}"; then
  expect "${percent_jobs[0]}_0" COMPLETED 0:0
  expect "${percent_jobs[0]}_1" COMPLETED 0:0
  expect "${percent_jobs[1]}" COMPLETED 0:0
  grep -q "Shard 1/2" "$percent.shards/logs/shard-1.out" 2>/dev/null &&
    grep -q "^100% of comparisons agree" "$percent.shards/logs/merge.out" && [[ -f $percent/index.md ]] ||
    fail "% in OUT: no logs or report at \"$percent\": $(find "$tmp" -maxdepth 1 -name 'pct*')"
fi

# 6. What submit.sh cannot give every task, or that would make sbatch misread it: exit status 2 and one line naming
# the argument, nothing submitted, no folder made (--profile was once submitted: every task wrote the one FILE).
records=$(scontrol -o show job | wc -l)
submit_refuses() {  # submit_refuses WHAT MESSAGE ARGS...: submit.sh ARGS refuses so (OUT $tmp/upfront)
  local what=$1 message=$2 status=0
  shift 2
  rm -rf -- "$tmp/upfront" "$tmp/upfront.shards"  # what an earlier case left (a failure, said there)
  "$src/scripts/slurm/submit.sh" --crankcheck "$crankcheck" --sbatch --partition=crankcheck "$@" >"$tmp/upfront.log" 2>&1 ||
    status=$?
  [[ $status == 2 && $(wc -l <"$tmp/upfront.log") == 1 && ! -e $tmp/upfront && ! -e $tmp/upfront.shards ]] &&
    grep -qF -- "$message" "$tmp/upfront.log" || { cat "$tmp/upfront.log"; fail "submit.sh, $what: exit status $status"; }
}
submit_refuses "--profile" "VALIDATE-ARGS: --profile: every shard would write the one FILE" \
  2 "$tmp/upfront" -- --quick "$campaign_scene" --profile "$tmp/profile.csv"
submit_refuses "--out" "VALIDATE-ARGS: --out:" 2 "$tmp/upfront" -- --quick --out="$tmp/elsewhere"
submit_refuses "--shard" "VALIDATE-ARGS: --shard:" 2 "$tmp/upfront" -- --quick --shard 0/2
submit_refuses "--sbatch WORD" "--sbatch: \"short\": not an option" --sbatch -p --sbatch short 2 "$tmp/upfront"
submit_refuses "--sbatch --output" "--sbatch: --output=x.out: submit.sh sets" --sbatch --output=x.out 2 "$tmp/upfront"
submit_refuses "--sbatch --outp" "--sbatch: --outp=x.out: submit.sh sets" --sbatch --outp=x.out 2 "$tmp/upfront"
submit_refuses "--sbatch -ox" "--sbatch: -ox.out: submit.sh sets" --sbatch -ox.out 2 "$tmp/upfront"
submit_refuses "--sbatch --dependency" "--sbatch: --dependency=singleton:" --sbatch --dependency=singleton 2 "$tmp/upfront"
submit_refuses "a backslash in SHARDS" "has a backslash" --shards "$tmp/up\\front.shards" 2 "$tmp/upfront"
[[ ! -e $tmp/up\\front.shards ]] || fail "submit.sh, a backslash in SHARDS: the folder was made"
submit_refuses "N = 100001" "N: 100001: expected a number of shards from 2" 100001 "$tmp/upfront"
submit_refuses "an empty OUT" "OUT: empty" 2 ""
submit_refuses "--shards OUT" "the same folder as OUT" --shards "$tmp/upfront" 2 "$tmp/upfront"
[[ $(scontrol -o show job | wc -l) == "$records" ]] || fail "submit.sh: a refused campaign was submitted all the same"

if ((failures)); then
  echo "$failures failure(s)" >&2
  exit 1
fi
echo "all shard recipes agree with one run; Slurm's merge refuses a failed or cancelled shard, naming it"
