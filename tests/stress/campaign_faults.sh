#!/usr/bin/env bash
# campaign_faults.sh - a deleted run directory and a full disk never wedge a campaign,
# tried N times (not in make check: minutes per try). Each try disturbs a campaign of 8
# short runs (300 grains, preset fast, 4 s), then runs the same `study run` again, and
# compares its export with an uninterrupted campaign's (the columns that say when, where
# and how often aside):
#   deleted  `rm -rf RUNS/NAME` at a seeded moment while the first runs shake (the
#            database, beside it, kept);
#   full     RUNS on a tmpfs of a seeded size (root), which fills at some write (an
#            argument file, a journal, a checkpoint, an HDF5 chunk, the database); after
#            the stop no run may be `failed` or `running`; then the tmpfs is made large.
# The seed of each try and its moment (or size) are printed, so that a failure can be
# replayed: SEED=S N=1 bash tests/stress/campaign_faults.sh.
#   usage: bash tests/stress/campaign_faults.sh [N]    (N tries of each, default 20)
# Knobs: SHAKE (default bin/shake; bin/study beside it), SEED (default: the time),
# KINDS ("deleted full"), OUT (build/stress/campaign_faults).
set -u
cd "$(dirname "$0")/../.."
REPO=$PWD
N=${1:-${N:-20}}
SHAKE=${SHAKE:-$REPO/bin/shake}
STUDY=${STUDY:-$(dirname "$SHAKE")/study}
SEED=${SEED:-$(date +%s)}
KINDS=${KINDS:-deleted full}
OUT=${OUT:-$REPO/build/stress/campaign_faults}
[ -x "$SHAKE" ] && [ -x "$STUDY" ] || { echo "FAIL setup: $SHAKE or $STUDY missing (make all)"; exit 2; }
rm -rf "$OUT" && mkdir -p "$OUT" && cd "$OUT" || exit 2
q() { sqlite3 -batch -noheader "$1" "$2"; }
declare -A NOK NBAD
for k in $KINDS; do NOK[$k]=0 NBAD[$k]=0; done
MOUNTED=""
trap '[ -n "$MOUNTED" ] && umount "$MOUNTED" 2>/dev/null' EXIT

cat >s.campaign <<'EOF'
[campaign]
name = s
seed = 5
replicates = 2
[scene]
preset = fast
n_grains = 300
width = 30
radius_ratio = 2
duration = 4
checkpoint_every = 0.5
snapshots = no
[grid]
frequency = 4, 5, 6, 7
EOF
# export without the columns that say when, where and how (tests/strip_how.sh)
. "$REPO/tests/strip_how.sh"
strip() { strip_how "$1"; }
t0=$(date +%s%N)
"$STUDY" run s.campaign --runs "$OUT/REF" --jobs 2 >ref.log 2>&1 || { echo "FAIL setup: the reference campaign: $(tail -n 2 ref.log)"; exit 2; }
"$STUDY" export s --runs "$OUT/REF" >ref.csv
REFMS=$((($(date +%s%N) - t0) / 1000000))
echo "# reference campaign: $REFMS ms; seed $SEED, $N tries of: $KINDS"
RANDOM=$SEED

# verdict KIND I RUNS WHY... : the same command again completes the campaign, exported as
# the reference; WHY (may be empty) is what the disturbed invocation already did wrong
verdict() {
	local kind=$1 i=$2 runs=$3 why=$4 rc
	"$STUDY" run s.campaign --runs "$runs" --jobs 2 >"$kind.$i.again.log" 2>&1
	rc=$?
	"$STUDY" export s --runs "$runs" >"$kind.$i.csv" 2>/dev/null
	[ "$rc" = 0 ] || why="$why again: exit $rc: $(tail -n 1 "$kind.$i.again.log" | cut -c1-200);"
	cmp -s <(strip ref.csv) <(strip "$kind.$i.csv") ||
		why="$why export differs: $(diff <(strip ref.csv) <(strip "$kind.$i.csv") | head -n 3 | cut -c1-200 | tr '\n' ' ');"
	if [ -z "$why" ]; then
		NOK[$kind]=$((NOK[$kind] + 1))
		echo "ok $kind.$i"
	else
		NBAD[$kind]=$((NBAD[$kind] + 1))
		echo "FAIL $kind.$i: $why"
	fi
}

for i in $(seq 1 "$N"); do
	for kind in $KINDS; do
		R="$OUT/$kind.$i"
		case $kind in
		deleted)
			# a moment within the first 60 % of the reference's time after the first
			# journal appears (the first runs shake): the campaign is not over yet
			ms=$((RANDOM % (REFMS * 6 / 10 + 1)))
			echo "# deleted.$i: rm -rf at $ms ms after the first run began shaking"
			"$STUDY" run s.campaign --runs "$R" --jobs 2 >"$kind.$i.log" 2>&1 &
			pid=$!
			for _ in $(seq 3000); do
				compgen -G "$R/s/*.h5.journal" >/dev/null && break
				kill -0 $pid 2>/dev/null || break
				sleep 0.01
			done
			sleep "$(awk -v m=$ms 'BEGIN { printf "%.3f", m / 1000 }')"
			rm -rf "${R:?}/s" 2>>"$kind.$i.log" # (files the driver makes meanwhile may stay)
			wait $pid
			verdict "$kind" "$i" "$R" ""
			;;
		full)
			# 150 to 1500 KB: from the database's first page to a few runs' files
			kb=$((150 + RANDOM % 1350))
			echo "# full.$i: a tmpfs of $kb KB"
			mkdir -p "$R"
			if ! mount -t tmpfs -o "size=${kb}k" tmpfs "$R" 2>/dev/null; then
				echo "# skip full: cannot mount a tmpfs here (not root?)"
				KINDS=${KINDS/full/}
				continue
			fi
			MOUNTED=$R
			"$STUDY" run s.campaign --runs "$R" --jobs 2 >"$kind.$i.log" 2>&1
			rc=$?
			why=""
			if [ -f "$R/study.db" ]; then
				# (a disk too small for the database's tables: none recorded)
				nf=$(q "$R/study.db" "SELECT COUNT(*) FROM run WHERE campaign = 's' AND state = 'failed'" 2>/dev/null) || nf=0
				nr=$(q "$R/study.db" "SELECT COUNT(*) FROM run WHERE campaign = 's' AND state = 'running'" 2>/dev/null) || nr=0
				[ "$nf" = 0 ] || why="$why failed runs after the stop: $nf;"
				[ "$nr" = 0 ] || why="$why runs left 'running' after the stop: $nr;"
			fi
			case $rc in 0 | 2) ;; *) why="$why the full disk gave exit $rc: $(tail -n 1 "$kind.$i.log" | cut -c1-200);" ;; esac
			mount -o remount,size=256m "$R"
			verdict "$kind" "$i" "$R" "$why"
			umount "$R" && MOUNTED=""
			;;
		esac
	done
done
for kind in $KINDS; do
	echo "$kind: ${NOK[$kind]} of $N tries completed with the uninterrupted export, ${NBAD[$kind]} did not"
done
bad=0
for kind in $KINDS; do bad=$((bad + NBAD[$kind])); done
[ "$bad" = 0 ]
