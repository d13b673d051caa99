#!/usr/bin/env bash
# validate_lammps.sh - `make validate-lammps` (issue #16, point 4): the flux profile
# Phi(D) of the engine against LAMMPS, a code no one here wrote, over an ensemble of
# settled beds.
#
#   1. BEDS settled beds (seeds 101, 102, ...; no intruder) prepared by the engine and
#      written as LAMMPS data files (write_lammps);
#   2. each bed shaken at FREQ Hz, A = AMP cm, for DURATION s in both codes:
#      bin/shake (the paper preset: gear5, dt = 5e-5 s; flux = yes), and LAMMPS
#      gran/hooke with tests/bench/lammps/vibrated_box.in (the deck whose physics
#      tests/integration/lammps_agreement.sh checks against the engine: Y, gamma_N,
#      gamma_S, mu, g, the wall disks' masses, velocity Verlet at the same dt) with
#      tests/bench/lammps/validate_strobe.in inserted before its run: every atom dumped
#      at the engine's stroboscopic steps;
#   3. Phi(D) of each run: the engine's from its run file (bin/dumpflux run: flux_read),
#      LAMMPS's from its dump by the engine's own crossing code (bin/dumpflux dump:
#      core/crossing.c, the lines of the engine's run of the same bed, the box offset
#      A sin(2 pi f t) taken off), both averaged over the periods after the first SKIP
#      of them (flux_profile);
#   4. the two compared bed by bed (bin/dumpflux compare: means and Student-t intervals
#      over the beds, the paired difference, the sign-flip test), written as a Markdown
#      fragment with a figure (PNG and PDF).
#
# Knobs (environment): VALIDATE_QUICK=1 (2 beds, 6 s: checks the pipeline, says
# nothing about agreement), VALIDATE_BEDS, VALIDATE_DURATION (s), VALIDATE_SKIP
# (fraction), VALIDATE_FREQ (Hz), JOBS (parallel runs, default 2), VALIDATE_WORK (run
# directory, default build/validate[-quick]), VALIDATE_OUT (where the .md and the
# figure go: docs for the full run, the run directory for the quick one),
# VALIDATE_REPORT=1 (steps 3 and 4 only, from the runs already in the run directory
# and the times they recorded: to redraw the report without running again).
# The runs are started under nice -n 5 here; run the script (or make) without nice.
# Exit status: 0 done (whatever the verdict: the fragment states it), 1 a step failed.
set -euo pipefail
REPO=$(cd "$(dirname "$0")/../.." && pwd)
cd "$REPO"
QUICK=${VALIDATE_QUICK:-0}
if [ "$QUICK" = 1 ]; then
	BEDS=${VALIDATE_BEDS:-2} DURATION=${VALIDATE_DURATION:-6}
	WORK=${VALIDATE_WORK:-build/validate-quick}
	OUT=${VALIDATE_OUT:-$WORK}
else
	BEDS=${VALIDATE_BEDS:-10} DURATION=${VALIDATE_DURATION:-80}
	WORK=${VALIDATE_WORK:-build/validate}
	OUT=${VALIDATE_OUT:-docs}
fi
FREQ=${VALIDATE_FREQ:-3.0}
SKIP=${VALIDATE_SKIP:-0.2}
AMP=2            # the paper's amplitude (cm)
JOBS=${JOBS:-2}
SHAKE=${VALIDATE_SHAKE:-$REPO/bin/shake}
DUMPFLUX=${VALIDATE_DUMPFLUX:-$REPO/bin/dumpflux}
DECK=$REPO/tests/bench/lammps/vibrated_box.in
STROBE=$REPO/tests/bench/lammps/validate_strobe.in
LMP=${LMP:-lmp}
T0=$(date +%s)

die() { echo "validate_lammps: $*" >&2; exit 1; }
command -v "$LMP" >/dev/null || die "$LMP (LAMMPS) not found: make deps installs the Debian package lammps"
command -v gnuplot >/dev/null || die "gnuplot not found: make deps"
[ -x "$SHAKE" ] && [ -x "$DUMPFLUX" ] || die "build first: $SHAKE, $DUMPFLUX"
# the deck's time step is the one the dump's steps are counted in
DT=$(awk '$1 == "timestep" { print $2; exit }' "$DECK")
[ -n "$DT" ] || die "no timestep line in $DECK"
STEPS=$(awk -v d="$DURATION" -v dt="$DT" 'BEGIN { s = d / dt; r = int(s + 0.5); if (s - r > 1e-6 || r - s > 1e-6) exit 1; print r }') ||
	die "DURATION $DURATION s is not a whole number of steps of $DT s"

REPORT=${VALIDATE_REPORT:-0}
mkdir -p "$WORK/bin" "$OUT"
WORK=$(cd "$WORK" && pwd)
SEEDS=$(seq 101 $((100 + BEDS)))
if [ "$REPORT" = 1 ]; then
	[ -s "$WORK/times" ] || die "VALIDATE_REPORT=1: no runs recorded in $WORK (run without it first)"
	for s in $SEEDS; do
		[ -s "$WORK/shake_$s.h5" ] && [ -s "$WORK/lmp_$s.dump" ] || die "VALIDATE_REPORT=1: bed $s's runs are missing in $WORK"
	done
else
	rm -f "$WORK"/*.h5 "$WORK"/*.dump "$WORK"/*.tsv "$WORK"/*.log "$WORK"/jobs "$WORK"/*.sec "$WORK"/times
fi
# the binaries copied first: others may rebuild bin/ while the runs go on; a report
# from recorded runs reads their files with the binaries they were made with
if [ "$REPORT" != 1 ]; then
	cp "$SHAKE" "$WORK/bin/shake" && cp "$DUMPFLUX" "$WORK/bin/dumpflux" || die "cannot copy the binaries"
fi
[ -x "$WORK/bin/dumpflux" ] || die "no $WORK/bin/dumpflux"
SHAKE=$WORK/bin/shake DUMPFLUX=$WORK/bin/dumpflux

# the LAMMPS input: the deck with the strobe dump before its one `run ${steps}` line
awk 'FNR == NR { frag = frag $0 "\n"; next } /^run \$\{steps\}[ \t]*$/ { printf "%s", frag; n++ } { print }
	END { if (n != 1) exit 1 }' "$STROBE" "$DECK" >"$WORK/validate.in" ||
	die "$DECK: expected exactly one 'run \${steps}' line to insert the dump before"

echo "validate_lammps: $BEDS beds, $DURATION s at $FREQ Hz (A = $AMP cm), transient $SKIP of the periods, $JOBS jobs, in $WORK" >&2

if [ "$REPORT" != 1 ]; then
# 1. the beds (settled by the engine; frequency and amplitude only set the wall
#    velocities the data file carries for t = 0)
for s in $SEEDS; do
	nice -n 5 "$SHAKE" radius_ratio=0 seed="$s" frequency="$FREQ" amplitude=$AMP duration=0 progress=no \
		write_lammps="$WORK/bed_$s.data" output="$WORK/prep_$s.h5" >"$WORK/prep_$s.log" 2>&1 ||
		die "preparing bed $s failed: $(tail -c 300 "$WORK/prep_$s.log")"
done
T1=$(date +%s)

# 2. the runs, LAMMPS's first (the longer ones), JOBS at a time; each records its wall
#    and CPU (user, system) seconds
{
	for s in $SEEDS; do
		printf 'lmp %s\n' "$s"
	done
	for s in $SEEDS; do
		printf 'shake %s\n' "$s"
	done
} >"$WORK/jobs"
job() { # CODE SEED
	local code=$1 s=$2 rc=0 TIMEFORMAT='%R %U %S'
	if [ "$code" = lmp ]; then
		{ time OMP_NUM_THREADS=1 nice -n 5 "$LMP" -in "$WORK/validate.in" -log none -screen none -nocite \
			-var data "$WORK/bed_$s.data" -var steps "$STEPS" -var freq "$FREQ" -var amp "$AMP" \
			-var strobe "$WORK/lmp_$s.dump" >"$WORK/lmp_$s.log" 2>&1; } 2>"$WORK/lmp_$s.sec" || rc=$?
	else
		{ time nice -n 5 "$SHAKE" particles="$WORK/bed_$s.data" settle=no radius_ratio=0 frequency="$FREQ" \
			amplitude=$AMP duration="$DURATION" flux=yes snapshots=no traj_rate=0 progress=no \
			output="$WORK/shake_$s.h5" >"$WORK/shake_$s.log" 2>&1; } 2>"$WORK/shake_$s.sec" || rc=$?
	fi
	echo "validate_lammps: $code bed $s: exit $rc, $(awk '{ printf "%.0f s (CPU %.0f s)", $1, $2 + $3 }' "$WORK/${code}_$s.sec")" >&2
	return $rc
}
export -f job
export WORK LMP SHAKE STEPS FREQ AMP DURATION
xargs -P "$JOBS" -L 1 bash -c 'job "$0" "$1"' <"$WORK/jobs" || die "a run failed (logs in $WORK)"
T2=$(date +%s)
# what the report states about the runs: start, preparation and runs wall seconds, jobs
echo "$(date -u -d @"$T0" '+%Y-%m-%d %H:%M UTC') $((T1 - T0)) $((T2 - T1)) $JOBS" >"$WORK/times"
fi
T2=$(date +%s)
read -r STARTD STARTT STARTZ PREP_S RUNS_S RUN_JOBS <"$WORK/times"

# 3. the profiles; the frame check of the LAMMPS dumps: the walls moved by the drive's
#    A sin(2 pi f t) (fix move wiggle), which dumpflux takes off the mobile disks
wall_dev=0 ybox=0
for s in $SEEDS; do
	"$DUMPFLUX" run "$WORK/shake_$s.h5" --skip "$SKIP" >"$WORK/shake_$s.tsv" || die "dumpflux run shake_$s.h5 failed"
	"$DUMPFLUX" dump "$WORK/lmp_$s.dump" --like "$WORK/shake_$s.h5" --amplitude $AMP --frequency "$FREQ" \
		--dt "$DT" --skip "$SKIP" >"$WORK/lmp_$s.tsv" || die "dumpflux dump lmp_$s.dump failed"
	read -r fr wd yb < <(awk '/^# frames/ { print $3, $17, $13; exit }' "$WORK/lmp_$s.tsv")
	[ "$fr" = "$(awk -v d="$DURATION" -v f="$FREQ" 'BEGIN { print int(d * f + 1e-9) + 1 }')" ] ||
		die "lmp_$s.dump has $fr frames"
	wall_dev=$(awk -v a="$wall_dev" -v b="$wd" 'BEGIN { print (b > a ? b : a) }')
	ybox=$(awk -v a="$ybox" -v b="$yb" 'BEGIN { print (b > a ? b : a) }')
done
awk -v w="$wall_dev" 'BEGIN { exit !(w < 1e-9) }' ||
	die "the LAMMPS walls did not move as A sin(2 pi f t): largest deviation $wall_dev cm (frame assumption broken)"
# shellcheck disable=SC2046
"$DUMPFLUX" compare $(printf "$WORK/shake_%s.tsv " $SEEDS) -- $(printf "$WORK/lmp_%s.tsv " $SEEDS) \
	>"$WORK/compare.tsv" || die "dumpflux compare failed"

# per bed: the surface and Phi through the plane (mean over the lines at 0.4-0.6 of the
# surface height, as bin/onset's), each code
plane() { awk -v s="$2" '!/^#/ && $2 >= 0.4 * s && $2 <= 0.6 * s { t += $3; n++ } END { printf "%.3f", n ? t / n : 0 }' "$1"; }
surface() { awk '/surface/ { for (i = 1; i <= NF; i++) if ($i == "surface") { print $(i + 1); exit } }' "$1"; }

# 4. the figure and the fragment
FIG=validate_lammps
[ "$QUICK" = 1 ] && FIG=validate_lammps_quick
awk '!/^#/' "$WORK/compare.tsv" >"$WORK/plot.tsv"
cat >"$WORK/plot.gp" <<GP
do for [fmt in "png pdf"] {
  if (fmt eq "png") { set terminal pngcairo size 900,900 font ",11"; set output "$OUT/$FIG.png" } \
  else { set terminal pdfcairo size 6.5in,6.5in font ",10"; set output "$OUT/$FIG.pdf" }
  set multiplot layout 2,1 title "Φ(D) at $FREQ Hz, A = $AMP cm, no intruder: the same $BEDS beds shaken by each code"
  set grid
  set key top left
  set ylabel "Φ (particles per period)"
  set format x ""
  set xlabel ""
  set lmargin 10
  set title "mean over the beds ± 95 % interval"
  plot "$WORK/plot.tsv" using (\$2-0.08):3:4 with yerrorbars pt 7 ps 0.5 lc rgb "#1f77b4" title "shakebox (gear5)", \
       "" using (\$2+0.08):5:6 with yerrorbars pt 5 ps 0.5 lc rgb "#d62728" title "LAMMPS gran/hooke"
  set format x "%g"
  set xlabel "D: height above the floor (cm)"
  set ylabel "ΔΦ (particles per period)"
  set title "paired difference shakebox − LAMMPS ± 95 % interval (filled: interval misses 0)"
  set key off
  plot "$WORK/plot.tsv" using 2:7:8 with yerrorbars pt 6 ps 0.5 lc rgb "#333333", \
       "" using 2:(\$10 == 0 ? \$7 : 1/0) with points pt 7 ps 0.8 lc rgb "#d62728", 0 with lines lc rgb "black" lw 1
  unset multiplot
}
GP
gnuplot "$WORK/plot.gp" || die "gnuplot failed"
[ -s "$OUT/$FIG.png" ] && [ -s "$OUT/$FIG.pdf" ] || die "the figure was not written"
T3=$(date +%s)

val() { awk -v k="$1" '$1 == "#" && $2 == k { print $3; exit }' "$WORK/compare.tsv"; }
# summed over a code's runs: wall seconds, CPU seconds ("?" when not recorded)
sumsec() { cat "$WORK"/"$1"_*.sec | awk '{ t += $1; c += $2 + $3; if (NF < 3) u = 1 } END { printf "%.0f", t }'; }
sumcpu() { cat "$WORK"/"$1"_*.sec | awk '{ c += $2 + $3; if (NF < 3) u = 1 } END { if (u) printf "?"; else printf "%.0f", c }'; }
ndis=$(val disagree) nl=$(val lines) nused=$(val lines_with_crossings)
maxt=$(val max_abs_t) chi2=$(val chi2_per_line) pmax=$(val p_max_abs_t) pchi=$(val p_chi2)
perms=$(awk '$1 == "#" && $2 == "perms" { $1 = $2 = ""; sub(/^ +/, ""); print; exit }' "$WORK/compare.tsv")
# the verdict: the lines' own intervals (at 95 % about 5 % of them miss 0 by chance) and
# the family-wise sign-flip tests (p < 0.05: the profiles differ beyond their intervals)
verdict=$(awk -v pm="$pmax" -v pc="$pchi" 'BEGIN { print (pm < 0.05 || pc < 0.05) ? "disagree" : "agree" }')
dislines=$(awk '!/^#/ && $10 == 0 { printf "%s%d (%.1f cm, t = %s)", n++ ? ", " : "", $1, $2, $9 }' "$WORK/compare.tsv")
cmd="make validate-lammps"
[ "$QUICK" = 1 ] && cmd="make validate-lammps VALIDATE_QUICK=1"
{
	echo "<!-- generated by tests/bench/validate_lammps.sh ($cmd); do not edit -->"
	echo "## Validation against LAMMPS: Φ(D) over an ensemble of beds"
	echo
	total=$((PREP_S + RUNS_S + T3 - T2))
	echo "Generated $(date -u '+%Y-%m-%d %H:%M UTC') at commit $(git rev-parse --short HEAD 2>/dev/null || echo '?')$(git diff --quiet HEAD -- core analysis tests/bench 2>/dev/null || echo ' (with uncommitted changes)') by \`$cmd\`"
	echo "(runs started $STARTD $STARTT $STARTZ). **Run time: $total s** of wall time ($((total / 60)) min) on a shared $(nproc)-core machine:"
	echo "preparation $PREP_S s, the $((2 * BEDS)) runs $RUNS_S s with $RUN_JOBS at a time, analysis $((T3 - T2)) s. Summed over the runs, LAMMPS"
	echo "$(sumsec lmp) s of wall time ($(sumcpu lmp) s CPU), shakebox $(sumsec shake) s ($(sumcpu shake) s CPU)$(awk -v a="$(sumcpu lmp)" -v b="$(sumcpu shake)" -v j="$RUN_JOBS" -v p="$PREP_S" 'BEGIN { if (a != "?" && b != "?") printf ": on %d idle cores the whole would take about %.0f min", j, ((a + b) / j + p) / 60 }')."
	echo "LAMMPS: $("$LMP" -h 2>/dev/null | awk 'NF { print; exit }' | sed 's/^ *//')."
	echo
	echo "**Setup.** $BEDS settled beds without intruder (seeds $(echo $SEEDS | awk '{ print $1 }')…$(echo $SEEDS | awk '{ print $NF }'); 950 grains, width 60 cm, the paper's"
	echo "contact law), prepared by the engine and written as LAMMPS data files (\`write_lammps\`); each"
	echo "shaken for $DURATION s at f = $FREQ Hz, A = $AMP cm (Γ = $(awk -v f="$FREQ" -v a=$AMP 'BEGIN { printf "%.2f", a * (2 * 3.14159265358979 * f) ^ 2 / 981 }'))"
	echo "by **shakebox** (\`bin/shake\`, paper preset: gear5, Δt = 5·10⁻⁵ s, box frame) and by **LAMMPS**"
	echo "\`gran/hooke\` (\`tests/bench/lammps/vibrated_box.in\`: the same Y, γ_N, γ_S, μ, g, masses and wall"
	echo "disks; velocity Verlet \`nve/sphere disc\` at Δt = $DT s; walls moved by \`fix move wiggle\` in the lab"
	echo "frame). LAMMPS dumps every atom at the engine's stroboscopic steps (sample k at the first step at"
	echo "or after k/f; \`tests/bench/lammps/validate_strobe.in\`); \`bin/dumpflux\` reads the dump and counts the"
	echo "crossings with the engine's own code (\`core/crossing.c\`, which \`core/observe.c\` calls during a run)"
	echo "on the lines of the engine's run of the same bed, after taking the box offset A sin(2πft) off the"
	echo "heights (at most $(awk -v y="$ybox" 'BEGIN { printf "%.2g", y }') cm at a phase-0 step; the LAMMPS wall disks moved by exactly that, to"
	echo "$(awk -v y="$wall_dev" 'BEGIN { printf "%.1g", y }') cm, so lab and box frame are told apart correctly). Φ(D) per bed and code is the time"
	echo "mean over the periods after the first $(awk -v s="$SKIP" 'BEGIN { print s * 100 }') % of them ($(awk -v d="$DURATION" -v f="$FREQ" -v s="$SKIP" 'BEGIN { p = int(d * f + 1e-9); k = int(s * p); printf "%d of %d periods, %.0f s", p - k, p, (p - k) / f }'))."
	echo
	echo "**Statistics.** Per line: each code's mean over the beds ± the 95 % Student-t half-width; the"
	echo "paired difference shakebox − LAMMPS (bed by bed; the pairs are independent in practice, the"
	echo "trajectories decorrelate within seconds) with its interval and t = mean/(s/√n); *agree* = the"
	echo "difference's interval holds 0. With $nl lines about 5 % miss 0 by chance, and neighbouring lines"
	echo "are strongly correlated, so the verdict rests on two statistics over all lines with crossings"
	echo "($nused): max |t| and χ²/L = mean of t², whose null distributions come from the sign-flip test"
	echo "(each bed's difference as likely to have either sign if the codes agree; $perms, with the lines' correlations)."
	echo
	echo "**Result: the profiles $verdict.** Lines whose difference interval misses 0: $ndis of $nl${dislines:+ — $dislines}."
	echo "max |t| = $maxt (sign-flip p = $pmax); χ²/L = $chi2 (p = $pchi)."
	if [ "$verdict" = agree ]; then
		echo "Neither family-wise statistic is beyond what sign noise over $BEDS beds gives (p ≥ 0.05): Φ(D) from"
		echo "LAMMPS and from shakebox agree within their intervals."
	else
		echo "At least one family-wise statistic is beyond what sign noise over $BEDS beds gives (p < 0.05): Φ(D)"
		echo "from LAMMPS and from shakebox **differ** beyond their intervals (see the lines above and the figure)."
	fi
	# more lines outside than chance gives (binomial mean + 2 sd): say where and how large
	awk -v L="$nl" '!/^#/ && $10 == 0 { d += $7; b += $5; n++; if (!lo) lo = $2; hi = $2 }
		END { e = 0.05 * L + 2 * sqrt(0.05 * 0.95 * L); if (n > e && b != 0)
			printf "Note: %d lines outside is more than chance alone gives (about %.0f at most, for independent lines); they lie together, %.1f–%.1f cm, where the mean difference is %+.2f particles per period, %+.1f %% of LAMMPS'"'"'s Φ there. Lines are correlated (a bed with a stronger roll is stronger at every height), which the sign-flip p-values above account for; the difference is of the size of the per-line intervals and not significant over the profile with these beds, but it is systematic in sign: more beds would tell whether it is real.\n", n, e, lo, hi, d / n, 100 * d / b }' "$WORK/compare.tsv"
	[ "$QUICK" = 1 ] && echo "(Quick run: $BEDS beds of $DURATION s check the pipeline only; the verdict means nothing.)"
	echo
	echo "![Φ(D), shakebox and LAMMPS]($FIG.png) ([PDF]($FIG.pdf))"
	echo
	echo "Per bed: free-surface height and Φ through the plane (mean over the lines at 0.4–0.6 of the surface height)."
	echo
	echo "| seed | surface (cm) | Φ plane shakebox | Φ plane LAMMPS | shakebox run, wall (s) | LAMMPS run, wall (s) |"
	echo "|---:|---:|---:|---:|---:|---:|"
	for s in $SEEDS; do
		sf=$(surface "$WORK/shake_$s.tsv")
		echo "| $s | $(printf '%.2f' "$sf") | $(plane "$WORK/shake_$s.tsv" "$sf") | $(plane "$WORK/lmp_$s.tsv" "$sf") | $(awk '{ printf "%.0f", $1 }' "$WORK/shake_$s.sec") | $(awk '{ printf "%.0f", $1 }' "$WORK/lmp_$s.sec") |"
	done
	echo
	echo "Per line (D: mean height over the beds; Φ in particles per period; ± the 95 % half-width):"
	echo
	echo "| line | D (cm) | Φ shakebox | Φ LAMMPS | difference | t | agree |"
	echo "|---:|---:|---:|---:|---:|---:|:---:|"
	awk '!/^#/ { printf "| %d | %.2f | %.3f ± %.3f | %.3f ± %.3f | %+.3f ± %.3f | %.2f | %s |\n", $1, $2, $3, $4, $5, $6, $7, $8, $9, $10 ? "yes" : "**no**" }' "$WORK/compare.tsv"
} >"$OUT/$FIG.md.new"
mv "$OUT/$FIG.md.new" "$OUT/$FIG.md"
echo "validate_lammps: the profiles $verdict ($ndis of $nl lines outside; max |t| $maxt, p $pmax; chi2/L $chi2, p $pchi)" >&2
echo "validate_lammps: wrote $OUT/$FIG.md, $OUT/$FIG.png, $OUT/$FIG.pdf in $(($(date +%s) - T0)) s" >&2
