#!/usr/bin/env bash
# Runs the two farm recipes of docs/guide/splitting.md for real, on this one machine, and checks
# that they give the image of one whole render bit for bit:
#   - GNU parallel: `parallel ... tessera render SCENE --tiles {}/N ... -o part_{}.exr`, then
#     `tessera merge part_*.exr`;
#   - Slurm: the guide's `#SBATCH --array=1-N` job on a one-node cluster started here, then the
#     merge job submitted with `--dependency=afterok:JOBID`.
# Each is run on two scenes: the Cornell box with its <rfilter> element removed (so the film has
# Mitsuba's default filter, gaussian, whose footprint crosses tile borders) and
# scenes/materials.xml with a box filter, at 100x100 pixels (partial tiles at the edges), 8 spp,
# N=4 tile sets of the default 32-pixel tiles. "Bit for bit" is judged on the f32 pixel data: the
# PFM outputs of the merge and of one whole render must be byte-identical (whether the EXR files
# are also byte-identical is reported). A control, the same render with another seed, must differ.
#
# Why a script and not a test: it installs packages and starts system daemons (munged,
# slurmctld, slurmd), so it is a separate, documented command, not part of .ci/run.
#
#   bash scripts/farm_check.sh [TESSERA_BINARY]     (or TESSERA=... ; default target/release/tessera,
#                                                    built with cargo if absent)
#
# Assumes: Debian 12 (bookworm) or similar with apt-get, run as root, no systemd (the daemons are
# started directly), nothing else listening on Slurm's ports 6817/6818 and no other slurmctld or
# slurmd running. It installs `parallel`, `slurm-wlm` and `munge` when missing (quietly, skipped when
# present), creates /etc/munge/munge.key when absent and /run/munge, starts munged as the munge
# user unless one already answers, and runs slurmctld and slurmd as root (SlurmUser=root,
# SlurmdUser=root) from a slurm.conf in a temporary directory that also holds their state, spool
# and logs: one node, `$(hostname -s)` with the CPUs and memory `slurmd -C` reports,
# proctrack/linuxproc and task/none (no cgroups needed), no accounting. On exit, also on failure
# or Ctrl-C, it cancels its jobs, stops the daemons it started (by their process ids) and removes
# its temporary files. Prints a short report; exit code 0 only if both engines pass.
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
TESSERA=${1:-${TESSERA:-$repo/target/release/tessera}}
N=4
RES=100
SPP=8
TIMEOUT=300 # seconds to wait for the daemons and for the jobs

tmp=$(mktemp -d /tmp/farm_check.XXXXXX)
report="$tmp/report.txt"
: >"$report"

# --- cleanup: cancel our jobs, stop the daemons we started (pid files in $tmp), remove $tmp ---
cleanup() {
    local rc=$?
    set +e
    trap '' INT TERM PIPE # a second Ctrl-C or a closed output must not stop the cleanup
    # Cancel our jobs while the controller still runs (bounded: a few seconds at most).
    if [ -s "$tmp/jobs" ] && [ -s "$tmp/slurmctld.pid" ] && kill -0 "$(cat "$tmp/slurmctld.pid")" 2>/dev/null; then
        export SLURM_CONF="$tmp/slurm/slurm.conf"
        # shellcheck disable=SC2046
        timeout 5 scancel $(cat "$tmp/jobs") 2>/dev/null
        local until=$((SECONDS + 10))
        while [ $SECONDS -lt $until ] && [ -n "$(timeout 2 squeue -h 2>/dev/null)" ]; do sleep 0.2; done
    fi
    for d in slurmd slurmctld munged; do
        if [ -s "$tmp/$d.pid" ]; then
            pid=$(cat "$tmp/$d.pid")
            kill "$pid" 2>/dev/null
            for _ in $(seq 1 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
            kill -9 "$pid" 2>/dev/null
        fi
    done
    rm -rf "$tmp"
    exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

say() { echo "farm_check: $*"; }
now() { date +%s.%N; }
secs() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f s", b - a }'; }

# --- what it needs ---
install_deps() {
    local missing=()
    command -v parallel >/dev/null && parallel --version 2>/dev/null | grep -q 'GNU parallel' \
        || missing+=(parallel)
    command -v slurmctld >/dev/null && command -v slurmd >/dev/null && command -v sbatch >/dev/null \
        || missing+=(slurm-wlm)
    command -v munged >/dev/null || missing+=(munge)
    if [ ${#missing[@]} -eq 0 ]; then
        say "parallel, slurm-wlm, munge already installed"
        return
    fi
    say "installing ${missing[*]} with apt-get"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq >/dev/null
    apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

take_binary() {
    if [ ! -x "$TESSERA" ]; then
        if [ "$TESSERA" != "$repo/target/release/tessera" ]; then
            say "no executable tessera at $TESSERA"
            exit 2
        fi
        say "building $TESSERA"
        (cd "$repo" && cargo build --release -q -p tessera-cli)
    fi
    # The guide's commands call `tessera` by name: put this binary first on PATH under that name
    # (the Slurm jobs inherit this PATH).
    mkdir -p "$tmp/bin"
    ln -s "$(readlink -f "$TESSERA")" "$tmp/bin/tessera"
    export PATH="$tmp/bin:$PATH"
}

# --- the scenes: NAME SCENE_FILE -D ... ---
make_scenes() {
    mkdir -p "$tmp/scenes"
    grep -v '<rfilter' "$repo/scenes/cbox.xml" >"$tmp/scenes/cbox_default_filter.xml"
    ln -s "$repo/scenes/meshes" "$tmp/scenes/meshes"
    cases=(
        "cbox-gaussian|$tmp/scenes/cbox_default_filter.xml|-D res=$RES -D spp=$SPP"
        "materials-box|$repo/scenes/materials.xml|-D res=$RES -D spp=$SPP -D rfilter=box"
    )
    # The filters are what the names say (the cbox file names no rfilter: the default applies).
    local want name scene defs
    for c in "${cases[@]}"; do
        IFS='|' read -r name scene defs <<<"$c"
        want=${name##*-}
        # shellcheck disable=SC2086
        if ! tessera info "$scene" $defs 2>&1 | grep -Eq "^ *filter +$want(,|\$)"; then
            say "$name: tessera info does not report the $want filter"
            exit 1
        fi
    done
}

# One whole render (the expected bits) and a control with another seed, in DIR.
reference() {
    local dir=$1 scene=$2 defs=$3 ncpu
    ncpu=$(nproc)
    # shellcheck disable=SC2086
    (cd "$dir" && tessera render "$scene" $defs --threads "$ncpu" -q -o single.exr -o single.pfm \
        && tessera render "$scene" $defs --threads "$ncpu" -q --seed 1 -o control.pfm)
}

# Compares DIR/out.* with DIR/single.*; prints a verdict word and details.
verdict() {
    local dir=$1 exr
    if ! [ -s "$dir/out.pfm" ]; then
        echo "FAIL (no merged image)"
        return
    fi
    if cmp -s "$dir/control.pfm" "$dir/single.pfm"; then
        echo "FAIL (control: another seed gives the same bits, the comparison cannot fail)"
        return
    fi
    if cmp -s "$dir/out.exr" "$dir/single.exr"; then exr="EXR files byte-identical too"; else
        exr="EXR files differ in bytes"; fi
    if cmp -s "$dir/out.pfm" "$dir/single.pfm"; then
        echo "PASS (pixels bit-identical to one render; $exr; other seed differs)"
    else
        echo "FAIL (pixels differ from one render: $(tessera compare "$dir/out.pfm" "$dir/single.pfm" 2>&1 \
            | grep -E '^(RMSE|max abs error)' | tr -s ' \n' ' '))"
    fi
}

# --- GNU parallel, the guide's command shape ---
engine_parallel() {
    local name scene defs dir t0 t1 t2 jobs rc
    jobs=$(nproc)
    for c in "${cases[@]}"; do
        IFS='|' read -r name scene defs <<<"$c"
        dir="$tmp/parallel/$name"
        mkdir -p "$dir"
        cd "$dir"
        t0=$(now)
        rc=0
        # shellcheck disable=SC2086,SC2046
        parallel -j"$jobs" tessera render "$scene" $defs --tiles {}/$N --threads 1 -q \
            -o part_{}.exr ::: $(seq 1 $N) || rc=$?
        if [ $rc -ne 0 ]; then
            echo "parallel  $name: FAIL ($rc tile-set renders failed)" >>"$report"
            continue
        fi
        t1=$(now)
        tessera merge -q part_*.exr -o out.exr -o out.pfm || rc=$?
        if [ $rc -ne 0 ]; then
            echo "parallel  $name: FAIL (tessera merge exited $rc)" >>"$report"
            continue
        fi
        t2=$(now)
        reference "$dir" "$scene" "$defs"
        echo "parallel  $name: $N parts with parallel -j$jobs in $(secs "$t0" "$t1"), merge $(secs "$t1" "$t2"): $(verdict "$dir")" >>"$report"
    done
}

# --- Slurm: a one-node cluster here, the guide's array job, the merge with afterok ---
wait_for() { # SECONDS COMMAND...: true once COMMAND succeeds
    local until=$((SECONDS + $1))
    shift
    while [ $SECONDS -lt $until ]; do
        "$@" && return 0
        sleep 0.5
    done
    return 1
}
munge_ok() { munge -n 2>/dev/null | unmunge >/dev/null 2>&1; }
node_idle() { [ "$(sinfo -h -n "$node" -o %t 2>/dev/null)" = idle ]; }
jobs_gone() {
    local out
    out=$(squeue -h -j "$1" -o %i 2>/dev/null) || return 1
    [ -z "$out" ]
}

start_munge() {
    if munge_ok; then
        say "munged already running; using it"
        return
    fi
    if [ ! -s /etc/munge/munge.key ]; then
        say "creating /etc/munge/munge.key"
        mkdir -p /etc/munge
        mungekey --create --keyfile=/etc/munge/munge.key
    fi
    chown munge:munge /etc/munge/munge.key
    chmod 400 /etc/munge/munge.key
    mkdir -p /run/munge /var/lib/munge /var/log/munge
    chown munge:munge /run/munge /var/lib/munge /var/log/munge
    setpriv --reuid=munge --regid=munge --init-groups /usr/sbin/munged --foreground \
        >"$tmp/munged.log" 2>&1 &
    echo $! >"$tmp/munged.pid"
    if ! wait_for 20 munge_ok; then
        say "munged did not start: $(tail -n 3 "$tmp/munged.log" | tr '\n' ' ')"
        return 1
    fi
}

write_slurm_conf() {
    local conf=$1 d=$2 nodeline
    # `slurmd -C` prints this machine as a node line: NodeName=... CPUs=... RealMemory=...
    nodeline=$(slurmd -C | head -n 1)
    node=$(hostname -s)
    nodeline="NodeName=$node ${nodeline#* }"
    cat >"$conf" <<EOF
# One-node cluster for scripts/farm_check.sh; everything under $d.
ClusterName=farmcheck
SlurmctldHost=$node
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
SlurmctldPort=6817
SlurmdPort=6818
StateSaveLocation=$d/state
SlurmdSpoolDir=$d/spool
SlurmctldPidFile=$d/slurmctld.pid
SlurmdPidFile=$d/slurmd.pid
SlurmctldLogFile=$d/slurmctld.log
SlurmdLogFile=$d/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
MinJobAge=3600
DependencyParameters=kill_invalid_depend
$nodeline State=UNKNOWN
PartitionName=farm Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
}

engine_slurm() {
    local d="$tmp/slurm" name scene defs dir aid mid t0 t1 states cpus
    mkdir -p "$d/state" "$d/spool"
    for p in 6817 6818; do
        if ss -ltn | awk '{print $4}' | grep -q ":$p\$"; then
            say "port $p (Slurm's) is already in use here: $(ss -ltnp | grep ":$p " | tr -s " ")"
            return 1
        fi
    done
    start_munge
    write_slurm_conf "$d/slurm.conf" "$d"
    export SLURM_CONF="$d/slurm.conf"
    slurmctld -D -c -f "$SLURM_CONF" >"$d/slurmctld.out" 2>&1 &
    echo $! >"$tmp/slurmctld.pid"
    slurmd -D -f "$SLURM_CONF" >"$d/slurmd.out" 2>&1 &
    echo $! >"$tmp/slurmd.pid"
    t0=$(now)
    if ! wait_for "$TIMEOUT" node_idle; then
        say "node $node never became idle; sinfo: $(sinfo 2>&1 | tr '\n' ' ')"
        tail -n 5 "$d/slurmctld.log" "$d/slurmd.log" "$d/slurmctld.out" "$d/slurmd.out" 2>/dev/null
        return 1
    fi
    t1=$(now)
    say "slurm: node $node idle after $(secs "$t0" "$t1") ($(sinfo -h -o '%c CPUs, %m MB'))"
    cpus=$(sinfo -h -n "$node" -o %c)
    for c in "${cases[@]}"; do
        IFS='|' read -r name scene defs <<<"$c"
        dir="$tmp/slurm/$name"
        mkdir -p "$dir"
        cd "$dir"
        # The guide's array job, with this scene and node.
        cat >array.sh <<EOF
#!/bin/bash
#SBATCH --array=1-$N
#SBATCH --cpus-per-task=$cpus
tessera render $scene $defs --tiles \$SLURM_ARRAY_TASK_ID/$N --threads \$SLURM_CPUS_PER_TASK -q \\
    -o part_\$SLURM_ARRAY_TASK_ID.exr
EOF
        t0=$(now)
        aid=$(sbatch --parsable array.sh)
        aid=${aid%%;*}
        echo "$aid" >>"$tmp/jobs"
        mid=$(sbatch --parsable --dependency=afterok:"$aid" --wrap "tessera merge part_*.exr -o out.exr -o out.pfm")
        mid=${mid%%;*}
        echo "$mid" >>"$tmp/jobs"
        if ! wait_for "$TIMEOUT" jobs_gone "$aid,$mid"; then
            echo "slurm     $name: FAIL (jobs $aid, $mid not done after ${TIMEOUT} s)" >>"$report"
            continue
        fi
        t1=$(now)
        # Every array task and the merge job must have COMPLETED (exit code 0).
        states=$( { scontrol -o show job "$aid"; scontrol -o show job "$mid"; } 2>/dev/null \
            | grep -o 'JobState=[A-Z_]*' | cut -d= -f2)
        reference "$dir" "$scene" "$defs"
        if [ "$(grep -c . <<<"$states")" -ne $((N + 1)) ] || grep -qv '^COMPLETED$' <<<"$states"; then
            echo "slurm     $name: FAIL (job states: $(tr '\n' ' ' <<<"$states"); $(tail -q -n 2 slurm-*.out 2>/dev/null | tr '\n' ' '))" >>"$report"
            continue
        fi
        states="$N tasks + merge COMPLETED"
        echo "slurm     $name: array job $aid ($N tasks, --cpus-per-task=$cpus) + merge job $mid (afterok) in $(secs "$t0" "$t1") ($states): $(verdict "$dir")" >>"$report"
    done
}

# --- run ---
t_start=$(now)
install_deps
take_binary
make_scenes
say "$(tessera --version), $(nproc) CPUs, $(hostname -s); scenes ${RES}x${RES}, $SPP spp, $N tile sets"

set +e
# Each engine runs in a subshell with errexit on (its first failing command ends it); the subshell
# has its own signal traps, so Ctrl-C ends it and then the main shell's cleanup runs.
(trap 'exit 130' INT; trap 'exit 143' TERM; set -e; engine_parallel)
p_rc=$?
[ $p_rc -lt 128 ] || exit $p_rc
(trap 'exit 130' INT; trap 'exit 143' TERM; set -e; engine_slurm)
s_rc=$?
[ $s_rc -lt 128 ] || exit $s_rc
set -e
# An engine that stopped early (its messages are above) still gets its line.
[ $p_rc -eq 0 ] || echo "parallel  stopped: FAIL (exit code $p_rc; messages above)" >>"$report"
[ $s_rc -eq 0 ] || echo "slurm     stopped: FAIL (exit code $s_rc; messages above)" >>"$report"

echo
echo "farm_check report ($(secs "$t_start" "$(now)") in all)"
cat "$report"
result() { # ENGINE: PASS when it has report lines and none says FAIL
    if grep -q "^$1 " "$report" && ! grep "^$1 " "$report" | grep -q ': FAIL'; then
        echo PASS
    else
        echo FAIL
    fi
}
p=$(result parallel)
s=$(result slurm)
echo "GNU parallel: $p"
echo "Slurm:        $s"
[ "$p" = PASS ] && [ "$s" = PASS ]
