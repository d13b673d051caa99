#!/usr/bin/env bash
# movie.sh - bin/movie and the snapshots within a period: snapshots_per_period = N takes N
# snapshots a period at phases k/N (times checked), with the walls where the box was at
# each (/particles/walls/snapshot_position = the walls at rest moved by the box's offset),
# and N = 1 keeps the stroboscopic snapshots bit for bit; bin/movie makes an MP4 and a GIF
# that ffprobe decodes with one frame per snapshot drawn (all, or --from/--to), and
# a PNG of one frame; and it refuses, with the file named and nothing left behind: a run without snapshots, a file
# that is no run file, a movie name that is neither .mp4 nor .gif, a FIFO at the movie's
# place, bad option values, and an ffmpeg that fails or is missing.
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1
MOVIE=$(dirname "$SHAKE")/movie
[ -x "$MOVIE" ] || { fail setup "$MOVIE is not built (make)"; finish; }
command -v ffprobe >/dev/null || { fail setup "no ffprobe (Debian ffmpeg): run make deps"; finish; }

# N = 4 snapshots a period at f = 4 Hz over 0.5 s: t = k / 16, k = 0 .. 8
shake_run n4.log "${FAST[@]}" "${GENTLE[@]}" duration=0.5 snapshots_per_period=4 output=n4.h5 ||
	{ fail run "exit $?: $(tail -n 2 n4.log)"; finish; }
shake_run n1.log "${FAST[@]}" "${GENTLE[@]}" duration=0.5 output=n1.h5 || { fail run_n1 "exit $?: $(tail -n 2 n1.log)"; finish; }
shake_run n1x.log "${FAST[@]}" "${GENTLE[@]}" duration=0.5 snapshots_per_period=1 output=n1x.h5 ||
	{ fail run_n1x "exit $?: $(tail -n 2 n1x.log)"; finish; }
/usr/bin/python3 - n4.h5 n1.h5 >py.out 2>py.err <<'PY'
import sys, numpy as np, h5py
def check(name, cond, why=""):
    print(("ok " + name) if cond else ("FAIL %s: %s" % (name, why)))
with h5py.File(sys.argv[1], "r") as f:
    T = f["particles/bed/position/time"][...]
    dt = f["parameters"].attrs["dt"]
    check("n4.times", len(T) == 9 and np.all(np.abs(T - np.arange(9) / 16.0) <= dt + 1e-12), str(T))
    W = f["particles/walls/position"][...]
    S = f["particles/walls/snapshot_position/value"][...]
    off = f["particles/bed/box/offset/value"][...]
    want = (W[None, :, :] + np.stack([np.zeros_like(off[:, 1]), off[:, 1]], 1)[:, None, :]).astype(S.dtype)
    check("n4.walls_move_with_the_box", S.shape == (9,) + W.shape and np.array_equal(S, want), str(S.shape))
    check("n4.walls_share_the_clock", f["particles/walls/snapshot_position/time"][...].tolist() == T.tolist())
with h5py.File(sys.argv[2], "r") as f:
    T1 = f["particles/bed/position/time"][...]
    check("n1.once_a_period", len(T1) == 3 and "snapshot_position" not in f["particles/walls"], str(T1))
PY
while IFS= read -r l; do
	case $l in "ok "*) ok "${l#ok }" ;; "FAIL "*) l=${l#FAIL }; fail "${l%%: *}" "${l#*: }" ;; esac
done <py.out
[ -s py.err ] && fail python "$(tail -n 3 py.err)"
# N = 1 given is the run without the key, to the bit (the snapshots and the rest)
if same_output n1.h5 n1x.h5 output 2>same.err; then ok n1.same_as_default; else fail n1.same_as_default "$(head -n 3 same.err)"; fi

frames() { ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 "$1" 2>&1; }
if "$MOVIE" n4.h5 -o m.mp4 --no-progress >mp4.out 2>mp4.err && [ "$(frames m.mp4)" = 9 ]; then
	ok mp4.one_frame_per_snapshot
else
	fail mp4.one_frame_per_snapshot "$(tail -n 2 mp4.err) frames $(frames m.mp4)"
fi
contains mp4.err "9 frames" && ok mp4.says_its_cost || fail mp4.says_its_cost "$(head -n 1 mp4.err)"
[ "$(cat mp4.out)" = m.mp4 ] && ok mp4.prints_its_name || fail mp4.prints_its_name "$(cat mp4.out)"
if "$MOVIE" n4.h5 -o m.gif --color speed --from 0.1 --to 0.3 --no-progress >gif.out 2>gif.err &&
	[ "$(frames m.gif)" = 3 ]; then # t = 2/16, 3/16, 4/16
	ok gif.from_to
else
	fail gif.from_to "$(tail -n 2 gif.err) frames $(frames m.gif)"
fi
contains gif.err "speed scale 0 to" && ok gif.states_its_scale || fail gif.states_its_scale "$(cat gif.err)"
# a picture: the first frame drawn, a PNG
if "$MOVIE" n4.h5 --from 0.2 -o p.png --no-progress >/dev/null 2>png.err && [ "$(frames p.png)" = 1 ] &&
	[ "$(head -c 8 p.png | od -An -c | tr -d ' ')" = '211PNG\r\n032\n' ]; then
	ok png.one_picture
else
	fail png.one_picture "$(tail -n 2 png.err) frames $(frames p.png)"
fi
# the default name: the run's, .mp4, in the current directory
mkdir -p sub && (cd sub && "$MOVIE" ../n1.h5 --no-progress >/dev/null 2>&1) && [ "$(frames sub/n1.mp4)" = 3 ] &&
	ok default_name || fail default_name "$(ls sub)"

# refusals: exit status, the file named, nothing left
refused() { # NAME STATUS WORD CMD...
	local name=$1 want=$2 word=$3
	shift 3
	"$@" >r.out 2>r.err
	local rc=$?
	if [ "$rc" = "$want" ] && contains r.err "$word" && ! ls ./*.tmp.* >/dev/null 2>&1; then
		ok "refuse.$name"
	else
		fail "refuse.$name" "exit $rc (want $want), '$(head -n 1 r.err)' (want '$word'), left: $(ls ./*.tmp.* 2>/dev/null)"
	fi
}
shake_run ns.log "${FAST[@]}" "${GENTLE[@]}" snapshots=no output=ns.h5 || fail run_ns "exit $?"
refused no_snapshots 1 "ns.h5: the run has no snapshots" "$MOVIE" ns.h5 -o x.mp4
echo "not a run" >bogus.h5
refused not_a_run 2 bogus.h5 "$MOVIE" bogus.h5 -o x.mp4
refused missing 2 nothere.h5 "$MOVIE" nothere.h5 -o x.mp4
refused extension 1 ".mp4 or .gif (or .png" "$MOVIE" n4.h5 -o x.avi
mkfifo fifo.mp4
refused fifo 1 "a FIFO" "$MOVIE" n4.h5 -o fifo.mp4
refused fps 1 "--fps: expected a number in [1, 120]" "$MOVIE" n4.h5 --fps 0
refused width 1 "--width: expected a number in [64, 4096]" "$MOVIE" n4.h5 --width wide
refused from_to 1 "no snapshot in the times asked for" "$MOVIE" n4.h5 -o x.mp4 --from 5
refused option 1 "unknown option '--colour'" "$MOVIE" n4.h5 --colour speed
# an ffmpeg that fails: exit 3, its failure said, no movie and no temporary left
mkdir -p fakebin
printf '#!/bin/sh\necho "fake ffmpeg: no encoder" >&2\ncat >/dev/null\nexit 1\n' >fakebin/ffmpeg
chmod +x fakebin/ffmpeg
refused ffmpeg_fails 3 "ffmpeg failed" env PATH="$TMP/fakebin:$PATH" "$MOVIE" n4.h5 -o y.mp4 --no-progress
[ ! -e y.mp4 ] && ok ffmpeg_fails.no_movie || fail ffmpeg_fails.no_movie "y.mp4 left"
refused no_ffmpeg 3 "cannot run ffmpeg" env PATH="$TMP/nothing" "$MOVIE" n4.h5 -o z.mp4 --no-progress
"$MOVIE" --version | grep -q '^movie (' && ok version || fail version "$("$MOVIE" --version 2>&1)"
finish
