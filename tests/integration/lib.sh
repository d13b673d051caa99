# lib.sh - shared helpers of the integration scripts (sourced, not run).
# Each script prints "ok ID" or "FAIL ID: why" per check and ends with `finish`,
# which exits non-zero when any check failed.
set -u
SHAKE="${SHAKE:-$PWD/bin/shake}"
case "$SHAKE" in /*) ;; *) SHAKE="$PWD/$SHAKE" ;; esac
REPO="$PWD"
NFAIL=0
NOK=0
TMP=$(mktemp -d "${TMPDIR:-/tmp}/shake-it.XXXXXX")
trap 'rm -rf "$TMP"' EXIT

# Random moments (kills, faults) come from bash's RANDOM, seeded here and printed, so a
# failure reproduces: TEST_SEED=N bash tests/integration/NAME.sh
TEST_SEED=${TEST_SEED:-$(($(date +%s%N) % 1000000007))}
RANDOM=$TEST_SEED
echo "# random moments: TEST_SEED=$TEST_SEED"

ok() { echo "ok $1"; NOK=$((NOK + 1)); }
fail() { echo "FAIL $1: $2"; NFAIL=$((NFAIL + 1)); }
# skip ID WHY : a check that cannot run here; tests/run.sh shows and counts it
skip() { echo "SKIP $1: $2"; NSKIP=$((NSKIP + 1)); }
NSKIP=0
# check ID WHY COMMAND... : ok when the command succeeds
check() {
	local id=$1 why=$2
	shift 2
	if "$@"; then ok "$id"; else fail "$id" "$why"; fi
}
# a script that reached its end without one check has tested nothing: that fails
finish() {
	[ "$NFAIL" -eq 0 ] || exit 1
	if [ $((NOK + NSKIP)) -eq 0 ]; then
		echo "FAIL ${0##*/}: ran no check"
		exit 1
	fi
	exit 0
}

if [ ! -x "$SHAKE" ]; then
	fail setup "SHAKE=$SHAKE is not an executable (run make)"
	finish
fi

# A documentation page as a reader follows it (tutorial.sh, density_study.sh): the "$ "
# lines of its ```sh blocks, run in order and as written, each output checked.
# page_commands DOC N ID : CMDS, the page's commands, and the check ID.commands that there
# are N (a command added to the page without a check here fails)
page_commands() {
	mapfile -t CMDS < <(awk '/^```sh$/ { on = 1; next } /^```$/ { on = 0 } on && /^\$ / { sub(/^\$ /, ""); print }' "$1")
	[ "${#CMDS[@]}" = "$2" ] && ok "$3.commands" ||
		fail "$3.commands" "${1##*/} has ${#CMDS[@]} commands, this test checks $2: add the new one's check"
}
# page_run ID I : command I, its output (stdout and stderr) in outI; fails ID.cmdI.exit and
# returns 1 when it exits non-zero
page_run() {
	bash -c "${CMDS[$2]}" >"out$2" 2>&1
	local rc=$?
	[ "$rc" -eq 0 ] && return 0
	fail "$1.cmd$2.exit" "'${CMDS[$2]}' exited $rc: $(tail -c 600 "out$2")"
	return 1
}
# page_expect ID I PATTERN... : command I's output matches every extended regex (ID.cmdI)
page_expect() {
	local id=$1 i=$2 p
	shift 2
	for p in "$@"; do
		grep -qE -- "$p" "out$i" || { fail "$id.cmd$i" "'${CMDS[i]}' printed no line matching '$p': $(tail -c 600 "out$i")"; return; }
	done
	ok "$id.cmd$i"
}

# q DB SQL : the rows of one query of the SQLite database DB, columns joined by '|'. The
# scripts' one query helper (fixtures.sh fails on a script that defines its own).
q() { sqlite3 -batch -noheader -separator '|' "$1" "$2"; }
# reseal_rows DB: every result row's row seal (lib/rowseal.h) written again for the rows
# as they now are, by tests/integration/rowseal.py: for a test that edits rows on
# purpose, as the driver would have written them (a changed run file's new file seal)
reseal_rows() { /usr/bin/python3 "$REPO/tests/integration/rowseal.py" write "$1"; }

# study_setup : STUDY, bin/study beside $SHAKE unless the caller named one, or a failed setup
study_setup() {
	STUDY="${STUDY:-$(dirname "$SHAKE")/study}"
	[ -x "$STUDY" ] || { fail setup "STUDY=$STUDY is not an executable (run make)"; finish; }
}

# The tiny bed, spelt here and nowhere else (fixtures.sh fails on a script that spells its
# settling by hand): 60 grains in a box 20 wide, a 2x intruder one row deep, settled until
# the kinetic energy per disk is below 1 erg, at least 0.2 s; prepared in about 0.1 s.
TINY_BED=(n_grains=60 width=20 radius_ratio=2 depth=1 settle_ke=1 settle_min=0.2)
# A tiny, fast scene: the tiny bed shaken 0.2 s
FAST=("${TINY_BED[@]}" duration=0.2 snapshots=yes traj_rate=200 progress=no)
# Gentle shaking (Gamma = A (2 pi f)^2 / g = 0.64) that an exact number of periods
# fits into (1/f = 0.25 s).
GENTLE=(frequency=4 amplitude=1)

# tiny_bed [KEY=VALUE...] : BEDARGS, the tiny bed as KEY=VALUE words (a command line's), each
# KEY=VALUE given in place of the bed's own KEY (KEY=- leaves KEY out), other keys after
# the bed's in the order given
tiny_bed() {
	local kv a k seen=" "
	BEDARGS=()
	for kv in "${TINY_BED[@]}"; do
		k=${kv%%=*}
		seen+="$k "
		for a in "$@"; do [ "${a%%=*}" = "$k" ] && kv=$a; done
		[ "${kv#*=}" = - ] || BEDARGS+=("$kv")
	done
	for a in "$@"; do
		case $seen in *" ${a%%=*} "*) ;; *) [ "${a#*=}" = - ] || BEDARGS+=("$a") ;; esac
	done
}
# tiny_scene [KEY=VALUE...] : the same as the lines of a scene file ("key = value")
tiny_scene() {
	local kv
	tiny_bed "$@"
	for kv in "${BEDARGS[@]}"; do printf '%s = %s\n' "${kv%%=*}" "${kv#*=}"; done
}
# tiny_campaign NAME [SEED [SCENE-LINE...]] : the text of the tiny campaign NAME (seed 5
# unless given): four runs, two frequencies by two replicates that share a packing, of
# 40 grains shaken 0.2 s; the scene lines given follow the bed's
tiny_campaign() {
	local name=$1 seed=${2:-5}
	shift $(($# < 2 ? $# : 2))
	printf '[campaign]\nname = %s\nseed = %s\nreplicates = 2\n[scene]\n' "$name" "$seed"
	tiny_scene n_grains=40 width=16
	printf '%s\n' 'duration = 0.2' 'traj_rate = 100' 'snapshots = no' "$@" '[grid]' 'frequency = 4, 5'
}

# fixture_runs CAMPAIGN DIR [DRIVER] : DIR, the runs directory of CAMPAIGN run to its end by
# DRIVER (default $STUDY, --jobs 2), copied from a cache (FIXTURES, default build/fixtures)
# where the first script that asked for it left it: one campaign run per build, since its
# key is the campaign's text with the driver's and its engine's bits (a new build, a
# planted bug of make mutate, builds it anew). Returns the driver's exit code, its output
# in DIR.log; a campaign that did not end well is not kept.
fixture_runs() {
	local c=$1 dir=$2 drv=${3:-$STUDY} key root tmp rc
	case $drv in /*) ;; *) drv=$PWD/$drv ;; esac
	FIXTURES=${FIXTURES:-$REPO/build/fixtures}
	key=$(cat "$c" "$drv" "$(dirname "$drv")/shake" | sha256sum | cut -c1-16)
	root="$FIXTURES/${c##*/}.$key"
	if [ ! -f "$root/done" ]; then
		mkdir -p "$FIXTURES" && tmp=$(mktemp -d "$FIXTURES/.build.XXXXXX") || return 2
		cp "$c" "$tmp/${c##*/}" &&
			(cd "$tmp" && "$drv" run "${c##*/}" --runs "$tmp/R" --jobs 2 --no-progress >"$tmp/log" 2>&1)
		rc=$?
		if [ "$rc" -ne 0 ]; then
			cp "$tmp/log" "$dir.log"
			rm -rf "$tmp"
			return "$rc"
		fi
		sqlite3 "$tmp/R/study.db" "PRAGMA wal_checkpoint(TRUNCATE)" >/dev/null && : >"$tmp/done"
		# another script may have built it meanwhile: theirs stays, ours goes
		mv -T "$tmp" "$root" 2>/dev/null || rm -rf "$tmp"
		# the same campaign of earlier builds goes
		find "$FIXTURES" -maxdepth 1 -name "${c##*/}.*" ! -name "${c##*/}.$key" -mmin +60 -exec rm -rf {} + 2>/dev/null
	fi
	cp "$root/log" "$dir.log" && cp -r "$root/R" "$dir"
}

# term_at_checkpoint LOG OUT args... : runs $SHAKE args with output=OUT in the
# background and sends SIGTERM once OUT.ckpt exists (a state, not a fraction of an
# earlier run's wall time, which a loaded machine makes a race); returns the exit code
# (7: interrupted, as wanted)
term_at_checkpoint() {
	local log=$1 out=$2 pid i
	shift 2
	"$SHAKE" "$@" output="$out" progress=no >"$log" 2>&1 &
	pid=$!
	for ((i = 0; i < 1200; i++)); do
		[ -e "$out.ckpt" ] && break
		kill -0 $pid 2>/dev/null || break
		sleep 0.05
	done
	kill -TERM $pid 2>/dev/null
	wait $pid
}

# engine_of ID : REPLY, the pid of the engine running run ID (a process named shake with
# the argument run_id=ID, as the worker starts it: never the worker or a helper). Read
# from /proc with builtins alone, no process started: a loaded machine makes every fork
# dear, and a caller that must catch a run in a state of a few seconds polls it.
engine_of() {
	local d c a
	for d in /proc/[0-9]*; do
		{ read -r c <"$d/comm"; } 2>/dev/null && [ "$c" = shake ] || continue
		{ mapfile -d '' -t a <"$d/cmdline"; } 2>/dev/null || continue
		for c in "${a[@]}"; do
			[ "$c" = "run_id=$1" ] && { REPLY=${d#/proc/}; return 0; }
		done
	done
	return 1
}
# term_pending PID : a SIGTERM waits for the process (held by SIGSTOP): bit 15 of its
# pending signals, the process's or its main thread's (/proc/PID/status)
term_pending() {
	local k m
	{ while read -r k m; do
		case $k in ShdPnd: | SigPnd:) (((16#$m >> 14) & 1)) && return 0 ;; esac
	done <"/proc/$1/status"; } 2>/dev/null
	return 1
}

# shake_run LOG args... : runs $SHAKE with stdout+stderr into LOG; returns its exit code
shake_run() { # stderr-file args...
	local errf=$1
	shift
	"$SHAKE" "$@" >"$errf" 2>&1
}

# h5attrs FILE : every attribute of an HDF5 file into a table, "PATH<TAB>TYPE<TAB>VALUE"
# a line (TYPE as h5dump names it, H5T_IEEE_F64LE; VALUE the first line of its data,
# %.17g for reals, a string without its quotes); REPLY = the table's path. One h5dump
# per version of the file (made again unless the table is newer than the file), kept
# under $TMP: on these machines a start of h5dump costs about 30 ms (its forty shared
# libraries) and every fork is dear, and a script reads hundreds of attributes.
h5attrs() {
	[ -f "$1" ] || return 1
	REPLY="$TMP/.h5attrs/${1//\//%}"
	[ -e "$REPLY" ] && [ "$REPLY" -nt "$1" ] && return 0
	mkdir -p "$TMP/.h5attrs"
	h5dump -m %.17g -w 0 -A "$1" 2>/dev/null | awk -v OFS='\t' '
		function path(   i, p) {
			for (i = 1; i < n; i++)
				if (kind[i] == "GROUP" || kind[i] == "DATASET")
					p = name[i] == "/" ? "" : p "/" name[i]
			return p "/" name[n]
		}
		/^ *\(0\): / { if (kind[n] == "DATA" && kind[n - 1] == "ATTRIBUTE" && !got) {
				v = $0; sub(/^ *\(0\): /, "", v); if (v ~ /^".*"$/) v = substr(v, 2, length(v) - 2)
				val = v; got = 1 }
			next }
		/^ *DATATYPE / && kind[n] == "ATTRIBUTE" { type = $2 }
		/\{ *$/ { n++; kind[n] = $1; name[n] = ""
			if ($1 == "GROUP" || $1 == "DATASET" || $1 == "ATTRIBUTE") {
				v = $0; sub(/^[^"]*"/, "", v); sub(/" *\{ *$/, "", v); name[n] = v }
			if ($1 == "ATTRIBUTE") { type = ""; val = ""; got = 0 }
			next }
		/^ *\} *$/ { if (kind[n] == "ATTRIBUTE") print path(), type, val
			n--; next }' >"$REPLY.$$" && mv "$REPLY.$$" "$REPLY"
}

# attr FILE PATH : value of a scalar attribute (strings without quotes), %.17g for reals;
# empty when it does not exist. attrtype FILE PATH : its type (H5T_STD_I64LE, ...).
# A path the table does not list (none such, or an object reached through a second hard
# link, which h5dump shows once) is asked of h5dump itself.
attr_field() { # FIELD FILE PATH
	h5attrs "$2" || return 0
	awk -F'\t' -v p="$3" -v k="$1" '$1 == p { print $k; found = 1; exit } END { exit !found }' "$REPLY" && return 0
	h5dump -m %.17g -w 0 -a "$3" "$2" 2>/dev/null | awk -v k="$1" '
		k == 2 && /^ *DATATYPE / { print $2; exit }
		k == 3 && /^ *\(0\): / { sub(/^ *\(0\): /, ""); if ($0 ~ /^".*"$/) $0 = substr($0, 2, length($0) - 2); print; exit }'
}
attr() { attr_field 3 "$1" "$2"; }
attrtype() { attr_field 2 "$1" "$2"; }

# dims FILE DATASET : "d0 d1" (or "d0") of a dataset; empty when it does not exist.
dims() {
	h5dump -H -d "$2" "$1" 2>/dev/null | awk '/DATASPACE/ {
		s = $0; sub(/.*SIMPLE \{ \( */, "", s); sub(/ *\).*/, "", s); gsub(/,/, "", s); print s; exit }'
}

# h5vals FILE DATASET : every value of a dataset, one per line (%.17g), in storage
# order (row-major: a [K][n][2] position dataset gives x, y of disk 0 at snapshot 0 first)
h5vals() {
	h5dump -m %.17g -d "$2" -y -w 0 "$1" 2>/dev/null | awk '/DATA \{/ && !done { on = 1; next } on && /\}/ { on = 0; done = 1 }
		on { gsub(/,/, " "); for (i = 1; i <= NF; i++) print $i }'
}

# h5param FILE KEY : a scene parameter of a run file (an attribute of /parameters)
h5param() { attr "$1" "/parameters/$2"; }

# h5traj FILE : the intruder's trajectory (H5MD group /particles/intruder) as rows
# "t x y vx vy omega" (lab frame)
h5traj() {
	local g=/particles/intruder
	paste -d' ' <(h5vals "$1" $g/position/time) <(h5vals "$1" $g/position/value | paste -d' ' - -) \
		<(h5vals "$1" $g/velocity/value | paste -d' ' - -) <(h5vals "$1" $g/angular_velocity/value)
}

# h5snap FILE C : the snapshots' coordinate C (0 = x, 1 = y) of every mobile disk,
# one snapshot per line (from /particles/bed/position)
h5snap() {
	local n
	n=$(dims "$1" /particles/bed/id)
	h5vals "$1" /particles/bed/position/value | awk -v c="$2" -v n="$n" '
		(NR - 1) % 2 == c { row = row (row == "" ? "" : " ") $1; if (++k == n) { print row; row = ""; k = 0 } }'
}

# dump_noprov FILE [ATTR...] : the whole file as text (%.17g, exact for doubles), without the first
# line (it names the file), without the /provenance and /h5md groups (who ran it, where,
# with which build: /h5md/author is the user, whom ssh and a login shell name differently)
# and without the named root or /parameters attributes (e.g. output, whose value is the
# path the run was given); nor the root's digest, which covers /provenance and /h5md too
# (docs/inputs.md, "Run files").
dump_noprov() {
	local f=$1
	shift
	h5dump -m %.17g "$f" | awk -v skipattrs=" digest $* " 'NR == 1 { next }
		/^   GROUP "(provenance|h5md)" \{/ { skip = 1; end = "^   }$"; next }
		/^   GROUP "parameters" \{/ { inparams = 1 }
		inparams && /^   }$/ { inparams = 0 }
		!skip && /^   ATTRIBUTE "/ { a = $2; gsub(/"/, "", a); if (index(skipattrs, " " a " ")) { skip = 1; end = "^   }$"; next } }
		!skip && inparams && /^      ATTRIBUTE "/ { a = $2; gsub(/"/, "", a); if (index(skipattrs, " " a " ")) { skip = 1; end = "^      }$"; next } }
		skip && $0 ~ end { skip = 0; next }
		!skip { print }'
}

# same_output A B [ATTR...] : the two run files are identical apart from /provenance and /h5md (prints the
# first differing lines on stderr when they differ); ATTRs are root or /parameters
# attributes to ignore
same_output() {
	local a=$1 b=$2
	shift 2
	local da="$TMP/.da.$$" db="$TMP/.db.$$"
	dump_noprov "$a" "$@" >"$da" || return 1
	dump_noprov "$b" "$@" >"$db" || return 1
	[ -s "$da" ] || return 1
	if ! cmp -s "$da" "$db"; then
		diff "$da" "$db" | head -n 6 >&2
		return 1
	fi
	# and h5diff agrees (every dataset and attribute, bar the ignored attributes)
	local out rc n
	out=$(h5diff --exclude-path /provenance --exclude-path /h5md "$a" "$b" 2>&1)
	rc=$?
	[ "$rc" -le 1 ] || { echo "h5diff failed: $out" >&2; return 1; }
	for n in digest "$@"; do
		out=$(printf "%s\n" "$out" | grep -vF "attribute: <$n of </>> and <$n of </>>" |
			grep -vF "attribute: <$n of </parameters>> and <$n of </parameters>>")
	done
	out=$(printf "%s\n" "$out" | grep -vE "^([0-9]+ differences? found)?\$")
	[ -z "$out" ] || { printf "%s\n" "$out" | head -n 6 >&2; return 1; }
}

# h5shared_setup : H5SHARED, the directory of the links with the shared HDF5 beside $SHAKE
# (the Makefile's H5SHARED: the fault shim's hooks of HDF5's functions work only there), with
# each TOOL given there, or a failed setup
h5shared_setup() {
	H5SHARED="$(dirname "$SHAKE")/h5shared"
	local t
	for t in "$@"; do
		[ -x "$H5SHARED/$t" ] || { fail setup "$H5SHARED/$t is not an executable (run make tests)"; finish; }
	done
}

# analysis_tools_setup : BINDIR (the directory of $SHAKE) and STUDY, with the analysis
# tools beside them, or a failed setup
analysis_tools_setup() {
	BINDIR=$(dirname "$SHAKE")
	STUDY="${STUDY:-$BINDIR/study}"
	local t
	for t in "$STUDY" "$BINDIR/onset" "$BINDIR/waiting" "$BINDIR/figures" "$BINDIR/hysteresis"; do
		[ -x "$t" ] || { fail setup "$t is not an executable (run make)"; finish; }
	done
}

# data_driver_setup : DATA_STUDY, a copy of the driver under test ($STUDY) in $TMP/data/
# beside the release build of the engine ($SHAKE_DATA, default bin/shake, which make
# check builds first), for a campaign that only makes the files a tool under test reads.
# The sanitizer build of the engine runs long physics about eight times slower; its
# paths are checked by the scripts that test the engine, and both builds write the same
# bits (regression.sh). Without a release build, the engine under test is used.
data_driver_setup() {
	local rel=${SHAKE_DATA:-$REPO/bin/shake}
	[ -x "$rel" ] || rel=$SHAKE
	mkdir -p "$TMP/data" && cp "$STUDY" "$TMP/data/study" && cp "$rel" "$TMP/data/shake" ||
		{ fail setup "cannot copy the driver and the engine to $TMP/data"; finish; }
	DATA_STUDY=$TMP/data/study
}

# paper_figure_campaigns : t.campaign, h.campaign and w.campaign in the current directory,
# the tiny campaigns of the figures' checks (figures_paper.sh, figure_checks.sh): t with
# and without intruder at 3, 5, 7 Hz with flux and field; h an up-down ramp 3 -> 7 Hz; w
# 𝓡 = 2 and 3 at 6 Hz without flux or field (Fig. 4 only; every run is censored at 1 s,
# so its two Kaplan-Meier curves are one)
paper_figure_campaigns() {
	local scene
	scene="$(tiny_scene radius_ratio=-)
amplitude = 1
traj_rate = 100"
	printf '[campaign]\nname = t\nseed = 3\nreplicates = 2\n[scene]\n%s\nflux = yes\nduration = 1\nfield = yes\nfield_periods = 2\n[grid]\nradius_ratio = 0, 2\nfrequency = 3, 5, 7\n' "$scene" >t.campaign
	printf '[campaign]\nname = h\nseed = 4\nreplicates = 2\n[scene]\n%s\nflux = yes\nduration = 2.5\nramp = updown\nramp_from = 3\nramp_to = 7\n[grid]\nradius_ratio = 2\n' "$scene" >h.campaign
	printf '[campaign]\nname = w\nseed = 5\nreplicates = 3\n[scene]\n%s\nduration = 1\nfrequency = 6\n[grid]\nradius_ratio = 2, 3\n' "$scene" >w.campaign
}

# tool_quiet ID NAME ARGS... : runs the analysis tool NAME of $BINDIR (stdout ID.out, stderr
# ID.err); ok ID.exit_quiet when it exits 0 with nothing on stderr (no gnuplot warning)
tool_quiet() {
	local id=$1 n=$2
	shift 2
	"$BINDIR/$n" "$@" >"$id.out" 2>"$id.err"
	local rc=$?
	[ "$rc" -eq 0 ] && [ ! -s "$id.err" ] && ok "$id.exit_quiet" || fail "$id.exit_quiet" "exit $rc: $(head -c 400 "$id.err")"
}
# csv_col FILE NAME : the column number of NAME in a CSV file's header
csv_col() { head -n 1 "$1" | tr ',' '\n' | grep -nx "$2" | cut -d: -f1; }

# contains FILE STRING : fixed-string grep
contains() { grep -qF -- "$2" "$1"; }

# poll_until SECONDS COMMAND...: poll until the command succeeds (1 when it never did)
poll_until() {
	local end=$((SECONDS + $1))
	shift
	until "$@"; do
		[ "$SECONDS" -lt "$end" ] || return 1
		sleep 0.2
	done
}

# slurm_cluster_up: a one-node Slurm cluster for this script (scripts/slurm_local.sh:
# munged, slurmctld, slurmd under $TMP/cluster, own key, socket and ports), stopped and
# $TMP removed at its exit, SLURM_CONF exported, /usr/sbin on PATH; check slurm.cluster.
# Skips (and finishes) only where Slurm cannot be installed or run here.
slurm_cluster_up() {
	SLURM_LOCAL="$REPO/scripts/slurm_local.sh"
	local c t0=$SECONDS
	have_slurm() {
		for c in munged slurmctld slurmd sbatch squeue scancel scontrol; do
			command -v "$c" >/dev/null || [ -x "/usr/sbin/$c" ] || return 1
		done
	}
	PATH="$PATH:/usr/sbin"
	if ! have_slurm; then # the packages of make deps-test
		bash "$REPO/scripts/deps.sh" test >"$TMP/deps.log" 2>&1
		if ! have_slurm; then
			skip slurm "the Slurm packages (slurmctld slurmd slurm-client munge) are not installed and could not be: $(tail -n 1 "$TMP/deps.log")"
			finish
		fi
	fi
	if [ "$(id -u)" -ne 0 ]; then
		skip slurm "slurmd must run as root to start jobs, and this is uid $(id -u)"
		finish
	fi
	CL="$TMP/cluster"
	trap 'bash "$SLURM_LOCAL" stop "$CL" >/dev/null 2>&1; rm -rf "$TMP"' EXIT
	if ! bash "$SLURM_LOCAL" start "$CL" >"$TMP/start.out" 2>"$TMP/start.err"; then
		fail slurm.cluster "scripts/slurm_local.sh start: $(tail -n 8 "$TMP/start.err")"
		finish
	fi
	export SLURM_CONF="$CL/slurm.conf"
	[ "$(sinfo --noheader --format=%T)" = idle ] && grep -qx "export SLURM_CONF=$SLURM_CONF" "$TMP/start.out" &&
		ok slurm.cluster || fail slurm.cluster "node state '$(sinfo --noheader --format=%T)'"
	echo "# cluster up after $((SECONDS - t0)) s"
}
