#!/usr/bin/env bash
# study_ssh.sh - `study run --sshloginfile` for real: an OpenSSH server started here on
# 127.0.0.1 (own host key, own authorized key), two sshlogin entries pointing at it;
# the campaign runs through GNU parallel's --basefile/--transferfile/--return, the
# database stays local, and the outputs equal a local run of the same campaign. The
# engine that travels is the one beside the driver (one binary for every CPU: its
# kernel picks its path on each host). Then hosts that die:
# one down from the start (left out by --filter-hosts) and one whose ssh starts failing
# mid-campaign, killing the job it was running; the campaign completes and its export
# equals an uninterrupted local run's (timing and host columns aside).
# Every ssh goes through $TMP/ssh, which answers at once GNU parallel's four capacity
# probes of --filter-hosts (`parallel --number-of-sockets|cores|threads`,
# `--max-line-length-allowed`, run on each host at the start of every pass) with "0",
# parallel's own answer for a host without parallel: the logins say "1/" so nothing
# reads the numbers, and each probe cost a remote start of parallel (most of this
# script's time; under load they passed parallel's 10 s limit and every host was
# removed). Its login probe (`echo HOST`), the jobs and rsync go through real ssh, so a
# down host is still found by --filter-hosts itself.
# tier: slow: an OpenSSH server, two campaigns over ssh (GNU parallel checks every host first) and a local reference
. "$(dirname "$0")/lib.sh"
study_setup
cd "$TMP" || exit 1
# the driver finds what travels beside itself (study, shake), and its local worker the
# engine beside itself: the binaries under test
mkdir bin && cp "$STUDY" bin/study && cp "$SHAKE" bin/shake ||
	{ fail setup "cannot copy the binaries"; finish; }
STUDY="$TMP/bin/study"
SSHD=$(command -v sshd || echo /usr/sbin/sshd)
[ -x "$SSHD" ] || { fail ssh.setup "sshd is not installed (openssh-server; make deps)"; finish; }
command -v rsync >/dev/null || { fail ssh.setup "rsync is not installed (GNU parallel needs it for --transferfile/--return; make deps)"; finish; }
[ "$(id -u)" -eq 0 ] || { fail ssh.setup "needs root to start sshd with its own config"; finish; }

ssh-keygen -q -t ed25519 -N '' -f host_key && ssh-keygen -q -t ed25519 -N '' -f user_key || { fail ssh.setup keygen; finish; }
mkdir -p -m 700 "$HOME/.ssh"
AUTH="$TMP/authorized_keys"
# the sessions' HOME is an empty directory: bash, started by sshd, reads ~/.bashrc,
# which is the account's and not under test (on the machine this was measured on it
# started pyenv, a second of CPU and often several of waiting per session, past GNU
# parallel's 10 s limit for a probe under load); the login directory, and with it the
# remote work dir ~/.shakebox, stays the account's home
mkdir -p "$TMP/home" && printf 'environment="HOME=%s" %s\n' "$TMP/home" "$(cat user_key.pub)" >"$AUTH" && chmod 600 "$AUTH"
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
PermitUserEnvironment yes
C
mkdir -p /run/sshd
"$SSHD" -f "$TMP/sshd_config" -E "$TMP/sshd.log" || { fail ssh.setup "sshd did not start: $(cat sshd.log)"; finish; }
trap 'kill $(cat "$TMP/sshd.pid" 2>/dev/null) 2>/dev/null; rm -rf "$TMP" "$HOME/.shakebox/$NAME" "$HOME/.shakebox/${D:-none}"' EXIT
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
# parallel sends its remote command hex-encoded: the probes are answered from it
cat >ssh <<'W'
#!/bin/bash
cmd=$(perl -e 'print pack("H*", join("", grep { /^[0-9a-f]{16,}$/ } @ARGV))' -- "$@" 2>/dev/null | tr -d '\000')
case $cmd in *'`parallel --number-of-'* | *'`parallel --max-line-length-allowed`'*) echo 0; exit 0 ;; esac
exec ssh "$@"
W
chmod +x ssh
printf '1/%s -F %s h1\n1/%s -F %s h2\n' "$TMP/ssh" "$TMP/ssh_config" "$TMP/ssh" "$TMP/ssh_config" >logins

NAME="sshtest$$"
cat >s.campaign <<C
[campaign]
name = $NAME
seed = 3
replicates = 2
[scene]
$(tiny_scene n_grains=40 depth=-)
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
# what ran remotely was the engine beside the driver
cmp -s "$HOME/.shakebox/$NAME/shake" bin/shake && cmp -s "$HOME/.shakebox/$NAME/study" bin/study &&
	ok ssh.engine_sent || fail ssh.engine_sent "the remote engine or driver is not the one beside the driver"
# the same through the database: the exports equal but for when, where and how often
strip() {
	awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i ~ /^(attempts|started|finished|wall_seconds|host|git_hash|git_dirty|file)$/) drop[i] = 1 }
		{ s = ""; for (i = 1; i <= NF; i++) if (!drop[i]) s = s $i ","; print s }' "$1"
}
"$STUDY" export "$NAME" --runs "$TMP/S" >ssh.csv && "$STUDY" export "$NAME" --runs "$TMP/L" >local.csv &&
	[ "$(wc -l <ssh.csv)" = 5 ] && cmp -s <(strip ssh.csv) <(strip local.csv) && ok ssh.export_same_as_local ||
	fail ssh.export_same_as_local "$(diff <(strip local.csv) <(strip ssh.csv) | head -n 4 | cut -c1-300)"

# --- hosts that die ---
# h3 is down from the start; h2 dies under the second run it is given: its worker and
# engine are killed and its ssh cut (no output, no DONE line), and from then on every
# connection to it fails, as when a machine goes away
cat >down_ssh <<'W'
#!/bin/sh
exit 255
W
cat >dying_ssh <<W
#!/bin/bash
[ -e "$TMP/h2.dead" ] && exit 255
# parallel sends its remote command hex-encoded: is it a run's job, and which run?
cmd=\$(perl -e 'print pack("H*", join("", grep { /^[0-9a-f]{16,}\$/ } @ARGV))' -- "\$@" 2>/dev/null | tr -d '\\000')
id=\$(printf '%s' "\$cmd" | grep -ao 'study exec \. run [0-9a-f]*' | head -n 1 | awk '{ print \$5 }')
n=0
[ -n "\$id" ] && n=\$((\$(cat "$TMP/h2.runs" 2>/dev/null || echo 0) + 1)) && echo \$n >"$TMP/h2.runs"
"$TMP/ssh" "\$@" 0<&0 & # (rsync speaks through stdin: not /dev/null)
pid=\$!
[ "\$n" -ge 2 ] || { wait \$pid; exit; }
for i in \$(seq 100); do w=\$(pgrep -f "study exec . run \$id"); [ -n "\$w" ] && [ -n "\$(pgrep -P "\$w")" ] && break; sleep 0.02; done
sleep 0.2
touch "$TMP/h2.dead"
for p in \$w; do kill -KILL \$(pgrep -P \$p) \$p 2>/dev/null; done
kill -KILL \$pid
echo "\$id" >>"$TMP/h2.cut"
exit 255
W
chmod +x down_ssh dying_ssh
printf '1/%s -F %s h1\n1/%s -F %s h2\n1/%s -F %s h3\n' "$TMP/ssh" "$TMP/ssh_config" "$TMP/dying_ssh" "$TMP/ssh_config" \
	"$TMP/down_ssh" "$TMP/ssh_config" >logins3
D="dead$$"
sed "s/^name = .*/name = $D/; s/^duration = .*/duration = 3/" s.campaign >d.campaign
t0=$(date +%s%N)
"$STUDY" run d.campaign --runs "$TMP/DL" --jobs 2 --no-cache >dl.log 2>&1 || fail dead.local_reference "exit $?: $(tail -c 300 dl.log)"
echo "# local reference (4 runs of 3 s, 2 jobs): $((($(date +%s%N) - t0) / 1000000)) ms"
t0=$(date +%s%N)
"$STUDY" run d.campaign --runs "$TMP/DS" --sshloginfile "$TMP/logins3" --jobs 1 --no-cache >ds.log 2>&1
rc=$?
echo "# campaign over ssh, h2 dying under its second run, h3 down: $((($(date +%s%N) - t0) / 1000000)) ms"
[ "$rc" -eq 0 ] && [ "$(sqlite3 DS/study.db "SELECT COUNT(*) FROM run WHERE state = 'done'")" = 4 ] && ok dead.completes ||
	fail dead.completes "exit $rc: $(tail -c 600 ds.log)"
# the run h2 died under was still running there (no output yet), and was redone on h1
cut=$(head -n 1 h2.cut 2>/dev/null)
[ -n "$cut" ] && grep -q "h1.*run $cut\$" "DS/$D/joblog.txt" && ok dead.h2_died_mid_job_redone_on_h1 ||
	fail dead.h2_died_mid_job_redone_on_h1 "cut '$cut': $(cut -f2,9 "DS/$D/joblog.txt" | tr '\t' ' ')"
# h3 ran nothing: --filter-hosts left it out
! awk -F'\t' 'NR > 1 { print $2 }' "DS/$D/joblog.txt" | grep -q h3 && ok dead.down_host_filtered ||
	fail dead.down_host_filtered "$(cut -f2 "DS/$D/joblog.txt" | sort | uniq -c)"
"$STUDY" export "$D" --runs "$TMP/DS" >ds.csv && "$STUDY" export "$D" --runs "$TMP/DL" >dl.csv &&
	[ "$(wc -l <ds.csv)" = 5 ] && cmp -s <(strip ds.csv) <(strip dl.csv) && ok dead.export_same_as_local ||
	fail dead.export_same_as_local "$(diff <(strip dl.csv) <(strip ds.csv) | head -n 4 | cut -c1-300)"
finish
