#!/usr/bin/env bash
# Throwaway single-node Slurm (Debian bookworm, Slurm 22.05) + its own munged,
# everything (config, key, socket, state, logs, pids) inside one folder.
#
#   local_slurm.sh install             install the Debian packages if missing
#   local_slurm.sh start DIR           write DIR/slurm.conf + DIR/env, start daemons,
#                                      wait until the node is idle
#   local_slurm.sh wait DIR JOBID...   wait until the jobs leave the queue, print
#                                      every job's (array task's) final JobState,
#                                      fail unless all are COMPLETED
#   local_slurm.sh stop DIR            stop the daemons recorded in DIR (idempotent)
#
# Clients: `source DIR/env` (exports SLURM_CONF; give a path with a slash, as a
# bare `source env` finds /usr/bin/env on PATH first). Timeouts in seconds:
# LOCAL_SLURM_START_TIMEOUT (60), LOCAL_SLURM_WAIT_TIMEOUT (300).
set -Eeuo pipefail
export PATH="$PATH:/usr/sbin:/sbin"  # munged, slurmctld, slurmd live in sbin
DAEMONS=(slurmd slurmctld munged)    # stop order: reverse of start order

die() { echo "local_slurm: error: $*" >&2; exit 1; }
have() { local b; for b; do command -v "$b" >/dev/null || return 1; done; }

cmd_install() {
  local bins=(munged mungekey slurmctld slurmd sbatch squeue sinfo scontrol srun scancel)
  if ! have "${bins[@]}"; then
    # A fresh machine may have no package lists yet, so update once and retry.
    local apt=(apt-get install -y -q --no-install-recommends slurmctld slurmd slurm-client munge)
    DEBIAN_FRONTEND=noninteractive "${apt[@]}" >/dev/null 2>&1 ||
      { apt-get update -q >/dev/null && DEBIAN_FRONTEND=noninteractive "${apt[@]}" >/dev/null; } ||
      die "apt-get install of slurm/munge failed"
  fi
  have "${bins[@]}" || die "slurm/munge binaries still missing after install"
}

# abs_dir DIR: absolute path; Slurm's config parser does not cope with blanks.
abs_dir() {
  mkdir -p "$1"
  local d; d=$(cd "$1" && pwd)
  [[ $d != *[[:space:]]* ]] || die "DIR must not contain whitespace: $d"
  echo "$d"
}

# free_port [EXCLUDE]: a random TCP port nobody listens on (another run, a leftover daemon).
free_port() {
  local p i
  for i in $(seq 200); do
    p=$((20000 + (RANDOM * 32768 + RANDOM + i) % 40000))
    [[ $p != "${1:-}" ]] || continue
    ss -Hltn "sport = :$p" | grep -q . || { echo "$p"; return 0; }
  done
  return 1
}

# running PID NAME: PID runs and is NAME (guards against pid reuse). A zombie
# counts as gone: in some containers pid 1 reaps orphans late.
running() {
  [[ $1 =~ ^[0-9]+$ ]] || return 1
  [[ $(ps -o stat= -p "$1" | tr -d ' ') != Z* ]] || return 1
  [[ $(ps -o comm= -p "$1" | tr -d ' ') == "$2" ]]
}
# alive NAME DIR: the daemon recorded in DIR/run/NAME.pid is running.
alive() { running "$(cat "$2/run/$1.pid" 2>/dev/null)" "$1"; }

cmd_stop() {
  [[ -d $1 ]] || return 0
  local dir d pid i; dir=$(cd "$1" && pwd)
  # Cancel leftover jobs first, else their slurmstepd processes outlive slurmd.
  if alive slurmctld "$dir"; then
    SLURM_CONF="$dir/slurm.conf" timeout 10 scancel --quiet --user=root 2>/dev/null || true
    for i in $(seq 20); do
      [[ -z $(SLURM_CONF="$dir/slurm.conf" timeout 5 squeue -h -o %i 2>/dev/null) ]] && break
      sleep 0.5
    done
  fi
  for d in "${DAEMONS[@]}"; do
    # Read the pid once: the daemons delete their pid file early in shutdown.
    pid=$(cat "$dir/run/$d.pid" 2>/dev/null) || pid=""
    if running "$pid" "$d"; then
      kill -TERM "$pid" 2>/dev/null || true
      for i in $(seq 100); do running "$pid" "$d" || break; sleep 0.2; done
      if running "$pid" "$d"; then kill -KILL "$pid" 2>/dev/null || true; sleep 0.5; fi
      running "$pid" "$d" && die "could not stop $d (pid $pid)"
    fi
    rm -f "$dir/run/$d.pid"
  done
}

cmd_start() {
  local dir; dir=$(abs_dir "$1")
  [[ -z $(ls -A "$dir") ]] || die "$dir is not empty"
  have munged mungekey slurmctld slurmd sinfo || die "slurm/munge not installed; run: $0 install"
  # On any failure from here: one error line, the daemons' log tails, clean up.
  fail() {
    ((BASH_SUBSHELL == 0)) || exit 1  # inside $(...): let the main shell report once
    trap - ERR
    echo "local_slurm: error: $*" >&2
    local f; for f in "$dir"/log/*.log; do
      [[ -f $f ]] && { echo "---- $f" >&2; tail -n 15 "$f" >&2; }
    done
    cmd_stop "$dir" || true
    exit 1
  }
  trap 'fail "command failed (line $LINENO): $BASH_COMMAND"' ERR

  # munged requires every directory on the socket's path to be executable by all.
  chmod 0755 "$dir"
  mkdir -p "$dir"/{munge,state,spool,log,run}
  chmod 0755 "$dir/munge"
  mungekey --create --keyfile="$dir/munge/munge.key"  # root-owned, 0600: what munged (root) wants
  munged --socket="$dir/munge/munge.sock" --key-file="$dir/munge/munge.key" \
    --pid-file="$dir/run/munged.pid" --log-file="$dir/log/munged.log" \
    --seed-file="$dir/munge/munged.seed" || fail "munged did not start"

  # Node description from the hardware; RealMemory a bit lower, else slurmd
  # reports "Low RealMemory" and the node drains.
  local probe node hw mem cport dport
  probe=$(slurmd -C | head -n 1)
  node=$(sed -n 's/^NodeName=\([^ ]*\).*/\1/p' <<<"$probe")
  [[ -n $node ]] || fail "cannot parse 'slurmd -C': $probe"
  hw=$(tr ' ' '\n' <<<"$probe" | grep -Ev '^(NodeName|RealMemory)=' | tr '\n' ' ')
  mem=$(sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p' <<<"$probe")
  mem=$((mem * 9 / 10))
  cport=$(free_port) || fail "no free TCP port found"
  dport=$(free_port "$cport") || fail "no free TCP port found"

  : >"$dir/plugstack.conf"  # keep /etc/slurm/plugstack.conf.d/* out of the test
  cat >"$dir/slurm.conf" <<EOF
# Generated by tests/slurm/local_slurm.sh for a local test run.
ClusterName=local
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$cport
SlurmdPort=$dport
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
# Our own munged; honoured by clients, slurmctld, slurmd and slurmstepd.
AuthInfo=socket=$dir/munge/munge.sock
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/run/slurmctld.pid
SlurmdPidFile=$dir/run/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
PlugStackConfig=$dir/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
# Without a default, a job without --mem gets the whole node and jobs run one at a time.
DefMemPerCPU=256
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
ReturnToService=2
MailProg=/bin/true
# No accounting, so "scontrol show job" is the only record of final states: keep it an hour.
MinJobAge=3600
NodeName=$node NodeAddr=127.0.0.1 ${hw}RealMemory=$mem State=UNKNOWN
PartitionName=debug Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
  printf 'export SLURM_CONF=%q\nexport LOCAL_SLURM_DIR=%q\n' "$dir/slurm.conf" "$dir" >"$dir/env"

  export SLURM_CONF="$dir/slurm.conf"
  slurmctld -f "$SLURM_CONF" || fail "slurmctld did not start"
  slurmd -f "$SLURM_CONF" -N "$node" || fail "slurmd did not start"

  local t0=$SECONDS limit=${LOCAL_SLURM_START_TIMEOUT:-60} state=""
  while :; do
    state=$(timeout 10 sinfo -h -N -n "$node" -o %t 2>/dev/null || true)
    [[ $state == idle ]] && break
    local d; for d in "${DAEMONS[@]}"; do alive "$d" "$dir" || fail "$d exited during start-up"; done
    ((SECONDS - t0 < limit)) || fail "node $node not idle after ${limit}s (state: '${state:-none}')"
    sleep 0.5
  done
  trap - ERR
  echo "local_slurm: node $node idle after $((SECONDS - t0))s (ctld port $cport, slurmd port $dport); source $dir/env"
}

cmd_wait() {
  local dir; dir=$(cd "$1" && pwd) || die "no such DIR: $1"; shift
  (($# > 0)) || die "wait: no job ids given"
  export SLURM_CONF="$dir/slurm.conf"
  local ids limit=${LOCAL_SLURM_WAIT_TIMEOUT:-300} t0=$SECONDS
  ids=$(IFS=,; echo "$*")
  # squeue lists only pending/running/completing jobs, so empty output = all done.
  while [[ -n $(squeue -h -j "$ids" -o %i 2>/dev/null) ]]; do
    ((SECONDS - t0 < limit)) || die "jobs $ids still queued after ${limit}s"
    sleep 1
  done
  # `scontrol -o show job` prints one line per array task; needs MinJobAge not expired.
  local id out bad=0
  for id in "$@"; do
    out=$(scontrol -o show job "$id") || die "scontrol knows no job $id"
    while read -r jid state; do
      echo "$jid $state"
      [[ $state == COMPLETED ]] || bad=1
    done < <(awk '{ j = a = t = s = ""
      for (i = 1; i <= NF; i++) { split($i, kv, "=")
        if (kv[1] == "JobId") j = kv[2]; if (kv[1] == "ArrayJobId") a = kv[2]
        if (kv[1] == "ArrayTaskId") t = kv[2]; if (kv[1] == "JobState") s = kv[2] }
      print (a != "" ? a "_" t : j), s }' <<<"$out" | sort -V)
  done
  return "$bad"
}

case "${1:-}" in
  install) cmd_install ;;
  start) [[ $# -eq 2 ]] || die "usage: $0 start DIR"; cmd_start "$2" ;;
  stop) [[ $# -eq 2 ]] || die "usage: $0 stop DIR"; cmd_stop "$2" ;;
  wait) [[ $# -ge 3 ]] || die "usage: $0 wait DIR JOBID..."; shift; cmd_wait "$@" ;;
  *) die "usage: $0 install | start DIR | stop DIR | wait DIR JOBID..." ;;
esac
