#!/usr/bin/env bash
# study_ssh.sh - `study run --sshloginfile` for real: an OpenSSH server started here on
# 127.0.0.1 (own host key, own authorized key), two sshlogin entries pointing at it;
# the campaign runs through GNU parallel's --basefile/--transferfile/--return, the
# database stays local, and the outputs equal a local run of the same campaign.
. "$(dirname "$0")/lib.sh"
STUDY="${STUDY:-$(dirname "$SHAKE")/study}"
[ -x "$STUDY" ] || { fail setup "STUDY=$STUDY is not an executable (run make)"; finish; }
cd "$TMP" || exit 1
SSHD=$(command -v sshd || echo /usr/sbin/sshd)
[ -x "$SSHD" ] || { fail ssh.setup "sshd is not installed (openssh-server; make deps)"; finish; }
command -v rsync >/dev/null || { fail ssh.setup "rsync is not installed (GNU parallel needs it for --transferfile/--return; make deps)"; finish; }
[ "$(id -u)" -eq 0 ] || { fail ssh.setup "needs root to start sshd with its own config"; finish; }

ssh-keygen -q -t ed25519 -N '' -f host_key && ssh-keygen -q -t ed25519 -N '' -f user_key || { fail ssh.setup keygen; finish; }
mkdir -p -m 700 "$HOME/.ssh"
AUTH="$TMP/authorized_keys"
cp user_key.pub "$AUTH" && chmod 600 "$AUTH"
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])' 2>/dev/null || echo $((20000 + RANDOM % 20000)))
cat >sshd_config <<C
ListenAddress 127.0.0.1
Port $port
HostKey $TMP/host_key
AuthorizedKeysFile $AUTH
PermitRootLogin prohibit-password
PasswordAuthentication no
KbdInteractiveAuthentication no
UsePAM no
StrictModes no
PidFile $TMP/sshd.pid
C
mkdir -p /run/sshd
"$SSHD" -f "$TMP/sshd_config" -E "$TMP/sshd.log" || { fail ssh.setup "sshd did not start: $(cat sshd.log)"; finish; }
trap 'kill $(cat "$TMP/sshd.pid" 2>/dev/null) 2>/dev/null; rm -rf "$TMP" "$HOME/.shakebox/$NAME"' EXIT
cat >ssh_config <<C
Host h1 h2
  HostName 127.0.0.1
  Port $port
  User $(id -un)
  IdentityFile $TMP/user_key
  IdentitiesOnly yes
  StrictHostKeyChecking no
  UserKnownHostsFile /dev/null
  LogLevel ERROR
  BatchMode yes
C
for i in $(seq 50); do ssh -F ssh_config h1 true 2>/dev/null && break; sleep 0.1; done
ssh -F ssh_config h1 true 2>ssh.err && ok ssh.login || { fail ssh.login "$(cat ssh.err)"; finish; }
printf '1/ssh -F %s h1\n1/ssh -F %s h2\n' "$TMP/ssh_config" "$TMP/ssh_config" >logins

NAME="sshtest$$"
cat >s.campaign <<C
[campaign]
name = $NAME
seed = 3
replicates = 2
[scene]
n_grains = 40
width = 20
radius_ratio = 2
settle_ke = 1
settle_min = 0.2
amplitude = 1
duration = 0.2
traj_rate = 200
[grid]
frequency = 3, 4
C
t0=$(date +%s%N)
"$STUDY" run s.campaign --runs "$TMP/S" --sshloginfile "$TMP/logins" --jobs 1 >ssh_run.log 2>&1
rc=$?
echo "# campaign over ssh (4 runs + 2 packings, 2 logins): $((($(date +%s%N) - t0) / 1000000)) ms"
[ "$rc" -eq 0 ] && ok ssh.run || fail ssh.run "exit $rc: $(tail -c 600 ssh_run.log)"
[ "$(sqlite3 S/study.db "SELECT COUNT(*) FROM runs WHERE state = 'done' AND status = 'ok' AND from_cache")" = 4 ] &&
	ok ssh.ingested || fail ssh.ingested "$(sqlite3 S/study.db "SELECT id, state, status, from_cache FROM runs")"
# the work happened in the remote work dir (copied there, run there, copied back)
[ -n "$(ls "$HOME/.shakebox/$NAME/"*.h5 2>/dev/null)" ] && [ -x "$HOME/.shakebox/$NAME/shake" ] &&
	ok ssh.remote_workdir || fail ssh.remote_workdir "$(ls -a "$HOME/.shakebox/$NAME" 2>&1 | head)"
[ ! -e "$HOME/.shakebox/$NAME/study.db" ] && [ -s S/study.db ] && ok ssh.db_local || fail ssh.db_local "database on the remote side"
# both logins ran jobs (the joblog names the sshlogin of each job)
[ "$(awk -F'\t' 'NR > 1 { print $2 }' "S/$NAME/joblog.txt" | sort -u | wc -l)" = 2 ] && ok ssh.two_logins ||
	fail ssh.two_logins "$(cut -f2 "S/$NAME/joblog.txt" | sort | uniq -c)"
"$STUDY" run s.campaign --runs "$TMP/L" >local.log 2>&1 || fail ssh.local_run "$(tail -c 300 local.log)"
same=0
for f in L/$NAME/*.h5; do same_output "$f" "S/$NAME/$(basename "$f")" && same=$((same + 1)); done
[ "$same" = 4 ] && ok ssh.same_as_local || fail ssh.same_as_local "$same of 4 outputs identical to the local run"
finish
