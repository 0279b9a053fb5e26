#!/bin/bash
# make check-cluster: the scripts of scripts/cluster/ run as a student runs them, on a Slurm
# cluster and over ssh, both made of this machine alone. As root, in a network namespace
# whose one interface is the loopback, with everything under build/cluster: munged on its own
# socket, slurmctld and slurmd (this host the controller and the one node, its cores the
# node's CPUs) and an sshd with its own keys, on free ports of 127.0.0.1. Then:
#   - animation.sbatch as a 4-task array over the first 12 frames of camera_around_david;
#   - parallel.sh as 4 jobs over ssh, two job slots on the sshd;
#   each frame byte-identical (cmp) to the one process's render of the 12 frames;
#   - a shard given a scene file that does not exist: as a one-task array, which the job
#     completion log (sacct -c: no accounting database here) records as FAILED with exit
#     code 1, and as 2 parallel jobs, parallel's exit status 2 (its count of failed jobs).
# Every process started here is stopped by its PID, also when a step fails, and the keys,
# sockets and Slurm state are removed; the logs and configuration stay in build/cluster, and
# the frames too when a check failed.
# Needs slurm-wlm, munge, openssh-server and parallel installed (.ci/run installs them);
# without them it fails, never skips. Exit status 0 when every check passed, 1 otherwise.
set -euo pipefail

fail() { echo "check-cluster: FAIL: $*" >&2; exit 1; }

[ "$(id -u)" = 0 ] || fail "needs root (slurmd starts the jobs; SlurmUser=root)"
for tool in unshare ip ss munged mungekey munge slurmctld slurmd sbatch squeue sinfo sacct scancel sshd ssh ssh-keygen parallel python3 cmp; do
    command -v "$tool" >/dev/null || fail "$tool not found (apt-get install slurm-wlm munge openssh-server parallel python3 iproute2)"
done
# The whole check runs in a network namespace of its own, whose one interface is a loopback
# (127.0.0.1): Slurm 22.05's daemons listen on every address whatever slurm.conf says, and
# in here every address is this loopback, which nothing outside the namespace reaches.
# Where no namespace can be made (a container without the right), the check still runs,
# saying loudly that Slurm's ports are open on every address of the machine meanwhile.
if [ "${RT_CHECK_CLUSTER_NETNS:-}" != 1 ]; then
    if unshare --net -- true 2>/dev/null; then
        RT_CHECK_CLUSTER_NETNS=1 exec unshare --net -- "$0" "$@"
    fi
    echo "check-cluster: WARNING: no network namespace here (unshare --net fails): slurmctld and slurmd" \
        "listen on every address of this machine while the check runs" >&2
    RT_CHECK_CLUSTER_NETNS=0
fi
if [ "$RT_CHECK_CLUSTER_NETNS" = 1 ]; then
    ip link set lo up
    # glibc's getaddrinfo (AI_ADDRCONFIG, as Slurm asks for its listening address) finds no
    # IPv4 address where 127.0.0.1 is the only one; a second loopback address counts.
    ip address add 127.0.0.2/8 dev lo
fi
started=$SECONDS
cd "$(dirname "$0")/../.."
dir=$PWD/build/cluster
shared=${RT_SHARED_DIR:-../shared}
scenes=$shared/scenes/hw2/raven/camera_around_david
NFRAMES=12
TIMEOUT=120  # seconds for each Slurm array to finish

[ -x ./raytracer ] || fail "./raytracer not built"
frames=("$scenes"/*.json)
[ "${#frames[@]}" -ge "$NFRAMES" ] || fail "$scenes: fewer than $NFRAMES scene files"
frames=("${frames[@]:0:NFRAMES}")

daemons() {  # the daemons of the kind started here, whoever started them
    ps -eo pid,ppid,user,args | awk 'NR == 1 || $4 ~ /(^|\/)(munged|slurmctld|slurmd|slurmstepd|sshd)(:|$)/'
}
echo "== daemons running before:"
daemons

# --- stopping everything, whatever step failed ---
pids=()      # every daemon started here, in order of start
names=()
made_run_sshd=
cleaned=
alive() { local s; s=$(ps -o stat= -p "$1" 2>/dev/null) && [[ $s != Z* ]]; }
cleanup() {
    [ -n "$cleaned" ] && return
    cleaned=1
    set +e
    # Jobs still running (a step that timed out) end before their daemons.
    if [ -n "${SLURM_CONF:-}" ] && alive "${slurmctld_pid:-0}"; then
        timeout 5 scancel --full --quiet --user=root 2>/dev/null
        for _ in $(seq 50); do [ -z "$(timeout 5 squeue -h 2>/dev/null)" ] && break; sleep 0.2; done
    fi
    local i pid
    for ((i = ${#pids[@]} - 1; i >= 0; i--)); do
        pid=${pids[i]}
        alive "$pid" && kill "$pid"
        for _ in $(seq 100); do alive "$pid" || break; sleep 0.1; done
        alive "$pid" && { echo "check-cluster: ${names[i]} ($pid) did not stop on SIGTERM: SIGKILL"; kill -KILL "$pid"; }
        wait "$pid" 2>/dev/null
    done
    rm -rf "$dir/state" "$dir/spool"
    rm -f "$dir"/munge.key "$dir"/munge.seed "$dir"/munge.socket* "$dir"/*_key "$dir"/*_key.pub \
        "$dir"/id_ed25519* "$dir"/authorized_keys "$dir"/known_hosts "$dir"/*.pid
    [ -n "$made_run_sshd" ] && rmdir /run/sshd
    echo "== daemons running after:"
    daemons
}
trap cleanup EXIT
trap 'fail interrupted' INT TERM

start() {  # start NAME COMMAND...: in the background, its PID recorded, its log logs/NAME.out
    local name=$1; shift
    "$@" </dev/null >"$dir/logs/$name.out" 2>&1 &
    pids+=($!)
    names+=("$name")
}
wait_for() {  # wait_for SECONDS NAME COMMAND...: until COMMAND succeeds, while NAME runs
    local seconds=$1 name=$2 i; shift 2
    local deadline=$((SECONDS + seconds))
    while ! "$@" >/dev/null 2>&1; do
        for i in "${!names[@]}"; do
            [ "${names[i]}" = "$name" ] && ! alive "${pids[i]}" && fail "$name exited: $(tail -n 3 "$dir/logs/$name.out")"
        done
        [ "$SECONDS" -lt "$deadline" ] || fail "$name not ready after $seconds s: $(tail -n 3 "$dir/logs/$name.out")"
        sleep 0.2
    done
}

rm -rf "$dir"
mkdir -p "$dir"
chmod 755 "$dir"  # munged: every folder above its socket searchable by all
mkdir -p "$dir/state" "$dir/spool" "$dir/logs" "$dir/frames"
# Three free ports of 127.0.0.1 (slurmctld, slurmd, sshd), bound together so they differ.
read -r ctld_port slurmd_port ssh_port < <(python3 -c '
import socket
s = [socket.socket() for _ in range(3)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))')
node=$(hostname -s)
cpus=$(nproc)

# --- munge: a key of its own, a socket of its own ---
mungekey --create --keyfile="$dir/munge.key"
start munged munged --foreground --key-file="$dir/munge.key" --socket="$dir/munge.socket" \
    --pid-file="$dir/munged.pid" --seed-file="$dir/munge.seed"
wait_for 10 munged munge --socket="$dir/munge.socket" --no-input

# --- Slurm: this host as controller and node, on 127.0.0.1; job completions logged to a
# file, which sacct --completion reads (no slurmdbd) ---
cat >"$dir/slurm.conf" <<EOF
ClusterName=rtcheck
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge.socket
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$dir/jobcomp.txt
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
SwitchType=switch/none
ReturnToService=2
MailProg=/bin/true
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=check Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$dir/slurm.conf
start slurmctld slurmctld -D -f "$SLURM_CONF"
slurmctld_pid=${pids[-1]}
start slurmd slurmd -D -f "$SLURM_CONF" -N "$node"
node_idle() { [ "$(timeout 5 sinfo -h -n "$node" -o %t)" = idle ]; }
wait_for 30 slurmd node_idle

# --- sshd on 127.0.0.1: its own host key, a user key of its own, the host key pinned ---
ssh-keygen -q -t ed25519 -N '' -C rtcheck-host -f "$dir/ssh_host_ed25519_key"
ssh-keygen -q -t ed25519 -N '' -C rtcheck-user -f "$dir/id_ed25519"
cp "$dir/id_ed25519.pub" "$dir/authorized_keys"
echo "[127.0.0.1]:$ssh_port $(cat "$dir/ssh_host_ed25519_key.pub")" >"$dir/known_hosts"
cat >"$dir/sshd_config" <<EOF
ListenAddress 127.0.0.1:$ssh_port
HostKey $dir/ssh_host_ed25519_key
PidFile $dir/sshd.pid
AuthorizedKeysFile $dir/authorized_keys
AuthenticationMethods publickey
PasswordAuthentication no
KbdInteractiveAuthentication no
PermitRootLogin prohibit-password
UsePAM no
StrictModes no
PrintMotd no
LogLevel INFO
EOF
cat >"$dir/ssh_config" <<EOF
Host rtcheck
    HostName 127.0.0.1
    Port $ssh_port
    User $(id -un)
    IdentityFile $dir/id_ed25519
    IdentitiesOnly yes
    UserKnownHostsFile $dir/known_hosts
    StrictHostKeyChecking yes
    BatchMode yes
    ConnectTimeout 5
EOF
if [ ! -d /run/sshd ]; then  # sshd's privilege separation folder
    mkdir -m 755 /run/sshd
    made_run_sshd=1
fi
start sshd "$(command -v sshd)" -D -e -f "$dir/sshd_config"
wait_for 10 sshd ssh -F "$dir/ssh_config" rtcheck true

echo "== started: munged, slurmctld (port $ctld_port), slurmd (port $slurmd_port), sshd (port $ssh_port), all on 127.0.0.1:"
ps -o pid,args -p "$(IFS=,; echo "${pids[*]}")"
if [ "$RT_CHECK_CLUSTER_NETNS" = 1 ]; then
    echo "   the network namespace's one interface: $(ip -brief address)"
    echo "   listening in it: $(ss -ltnH | awk '{printf "%s ", $4}')"
fi

# --- the reference: one process renders the 12 frames ---
./raytracer -q -o "$dir/frames/one_process" "${frames[@]}"
compared=()
compare() {  # compare NAME FOLDER: the same frames, byte for byte, as one process's
    local name=$1 out=$2 f n=0
    for f in "$dir/frames/one_process"/*.png; do
        [ -f "$out/${f##*/}" ] || fail "$name: ${f##*/} not written"
        cmp -s "$f" "$out/${f##*/}" || fail "$name: ${f##*/} differs from one process's"
        n=$((n + 1))
    done
    [ "$n" -eq "$NFRAMES" ] || fail "one process wrote $n frames, not $NFRAMES"
    [ "$(find "$out" -type f | wc -l)" -eq "$n" ] || fail "$name: files beyond the $n frames in $out"
    compared+=("$name: $n of $NFRAMES frames byte-identical to one process's")
    echo "ok: ${compared[-1]}"
}
# The scripts take the frames as globs or names separated by spaces: here the 12 names.
export FRAMES="${frames[*]}"

slurm_wait() {  # slurm_wait JOBID: until the array left the queue
    local i
    for ((i = 0; i < TIMEOUT * 2; i++)); do
        [ -z "$(squeue -h -j "$1" 2>/dev/null)" ] && return 0
        sleep 0.5
    done
    squeue -j "$1"
    fail "Slurm job $1 not finished after $TIMEOUT s"
}
completions() {  # completions NAME: JobID|State|ExitCode of each finished task of job NAME
    sacct --completion --noheader --parsable2 --format=JobID,JobName,State,ExitCode 2>/dev/null |
        awk -F'|' -v name="$1" '$2 == name {print $1 "|" $3 "|" $4}'
}

# --- the Slurm array: 4 shards, one CPU each ---
job=$(OUT=$dir/frames/slurm sbatch --parsable --array=0-3 --cpus-per-task=1 --job-name=rt-frames \
    --output="$dir/logs/%x_%a.out" scripts/cluster/animation.sbatch)
echo "submitted: sbatch --array=0-3 --cpus-per-task=1 scripts/cluster/animation.sbatch: job $job"
slurm_wait "$job"
tasks=$(completions rt-frames)
echo "sacct --completion, job rt-frames (JobID|State|ExitCode):"
echo "$tasks" | sed 's/^/   /'
[ "$(grep -c '|COMPLETED|0:0$' <<<"$tasks")" -eq 4 ] || fail "Slurm array: not 4 tasks COMPLETED with exit code 0:0"
compare "Slurm array (4 tasks)" "$dir/frames/slurm"

# --- GNU parallel over ssh: 4 shards, two job slots on the sshd ---
ssh_before=$(grep -c 'Accepted publickey' "$dir/logs/sshd.out" || true)
OUT=$dir/frames/parallel SHARDS=4 THREADS=1 \
    scripts/cluster/parallel.sh --sshlogin 2/rtcheck --ssh "ssh -F $dir/ssh_config" --joblog "$dir/logs/parallel.joblog"
logins=$(($(grep -c 'Accepted publickey' "$dir/logs/sshd.out") - ssh_before))
hosts=$(awk 'NR > 1 {print $2}' "$dir/logs/parallel.joblog" | sort | uniq -c | awk '{print $1 " jobs on " $2}')
echo "parallel's job log: $hosts; sshd accepted $logins logins"
[ "$hosts" = "4 jobs on rtcheck" ] || fail "parallel: the 4 jobs did not all run through ssh on rtcheck"
compare "GNU parallel over ssh (4 jobs, 2 slots)" "$dir/frames/parallel"

# --- a shard given a scene file that does not exist: two real frames and a missing one ---
FRAMES="${frames[0]} ${frames[1]} $dir/no_such_frame.json"
job=$(OUT=$dir/frames/missing sbatch --parsable --array=0 --cpus-per-task=1 --job-name=rt-missing \
    --output="$dir/logs/%x_%a.out" scripts/cluster/animation.sbatch)
echo "submitted: FRAMES='<2 frames> $dir/no_such_frame.json' sbatch --array=0 scripts/cluster/animation.sbatch: job $job"
slurm_wait "$job"
task=$(completions rt-missing)
echo "sacct --completion, job rt-missing (JobID|State|ExitCode): $task"
echo "   its output: $(cat "$dir/logs/rt-missing_0.out")"
[ "$task" = "$job|FAILED|1:0" ] || fail "Slurm: the task with a missing scene file is not recorded as FAILED with exit code 1:0"
detected=("Slurm: job $job (one task, a missing scene file) recorded by sacct as FAILED, exit code 1:0")

rc=0
OUT=$dir/frames/missing SHARDS=2 THREADS=1 scripts/cluster/parallel.sh --sshlogin 2/rtcheck --ssh "ssh -F $dir/ssh_config" 2>"$dir/logs/parallel_missing.err" || rc=$?
echo "parallel.sh, 2 shards given a missing scene file: exit status $rc"
sed 's/^/   /' "$dir/logs/parallel_missing.err"
[ "$rc" -eq 2 ] || fail "parallel: exit status $rc, not 2 (2 failed jobs)"
[ -z "$(find "$dir/frames/missing" -type f 2>/dev/null)" ] || fail "a shard with a missing scene file wrote frames"
detected+=("GNU parallel over ssh: 2 shards given a missing scene file, exit status 2 (2 jobs failed)")

# --- stop everything; nothing of it may be left ---
cleanup
for pid in "${pids[@]}"; do
    alive "$pid" && fail "process $pid still running"
done
rm -rf "$dir/frames"
left=$(find "$dir" \( -type s -o -name '*key*' -o -name '*.pid' -o -name known_hosts -o -name authorized_keys \) -print)
[ -z "$left" ] || fail "left behind: $left"

echo "== check-cluster: passed in $((SECONDS - started)) s"
for line in "${compared[@]}" "${detected[@]}"; do echo "   $line"; done
echo "   ${#pids[@]} daemons started (${names[*]}), all stopped; no key, socket or pid file left in build/cluster"
