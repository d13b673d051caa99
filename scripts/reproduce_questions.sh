# reproduce_questions.sh - sourced by scripts/reproduce.sh: the questions the paper left
# open (campaigns/reproduce/q*.campaign). Three functions, called where reproduce.sh runs
# the claims' campaigns, their tools and writes their sections:
#   questions_run      run the questions' campaigns (resumable, like the claims')
#   questions_tools    run the analysis tools on them
#   questions_report   print their sections of REPRODUCTION.md (markdown on stdout)
# It uses reproduce.sh's helpers (q, val, iv, fig, counts, tool, campaign, cname, log,
# run_campaign, integrator) and its variables (QUESTIONS, W, ANA).
# Every number is computed here from the database or the tools' outputs.

declare -A QFILE QNAME
for c in q1_stiffness q2_width_onset q2_width_rise q3_periodic q4_large q5_long; do
	QFILE[$c]=$(campaign "$c.campaign")
	QNAME[$c]=$(cname "${QFILE[$c]}")
done
qwant() { case " $QUESTIONS " in *" $1 "*) return 0 ;; esac; return 1; }
campaigns_of_question() {
	case $1 in
	1) echo q1_stiffness ;; 2) echo q2_width_onset q2_width_rise ;; 3) echo q3_periodic ;;
	4) echo q4_large ;; 5) echo q5_long ;;
	esac
}

questions_run() {
	local k c
	for k in $QUESTIONS; do
		for c in $(campaigns_of_question "$k"); do run_campaign "question $k" "$c" "${QFILE[$c]}"; done
	done
}

questions_tools() {
	qwant 2 && tool waiting "${QNAME[q2_width_rise]}"
	qwant 3 && { tool onset "${QNAME[q3_periodic]}" --by sides; tool convect "${QNAME[q3_periodic]}"; }
	qwant 4 && tool waiting "${QNAME[q4_large]}"
	qwant 5 && { tool waiting "${QNAME[q5_long]}"; tool whale "${QNAME[q5_long]}"; }
	return 0
}

# onset_rows CAMPAIGN -> per [onset] group: grp estimate lo hi replicates runs found below above state
onset_rows() {
	q "SELECT grp, $(num estimate), $(num ci_lo), $(num ci_hi), replicates, runs, found, below, above, state
	   FROM onset_group WHERE campaign = '$1' ORDER BY point"
}
# key=value out of an onset group's label ("stiffness=3000000 gamma_n=100 dt=0.0002")
grp_get() { tr ' ' '\n' <<<"$1" | awk -F= -v k="$2" '$1 == k { print $2 }'; }
# Gamma = A (2 pi f)^2 / g of a frequency (A, g of the paper's scene)
gam() { awk -v f="$1" -v a="$2" -v g="$3" 'BEGIN { if (f + 0 == f) printf "%.3g", a * (6.283185307 * f) ^ 2 / g; else print "-" }'; }
# a gnuplot figure (PNG and PDF) from a script body: GPFIG OUTBASE <<'EOF' ... EOF
gpfig() {
	local base=$1 body
	body=$(cat)
	command -v gnuplot >/dev/null || return 0
	{ echo "set terminal pngcairo size 900,560 font 'sans,11'; set output '$base.png'"; echo "$body"
	  echo "set terminal pdfcairo size 6in,3.7in font 'sans,9'; set output '$base.pdf'; replot"; } |
		gnuplot >/dev/null 2>&1 || log "gnuplot failed for $base"
}

q_stiffness() {
	local n=${QNAME[q1_stiffness]} A G rows
	echo "## Open question 1: is the convection below Γ = 1 an effect of the soft contacts?"
	echo
	integrator "${QNAME[q1_stiffness]}" "${QFILE[q1_stiffness]}"
	echo
	echo "Experiments and hard-contact simulations of vibrated beds convect only above Γ ≈ 1; the"
	echo "paper's model convects at Γ ≈ 0.6. Here the contact stiffness Y goes from the paper's"
	echo "3·10⁶ to 3·10⁸ g/s² at a fixed restitution coefficient (γ_N ∝ √Y: at a fixed γ_N a stiffer"
	echo "contact is also more elastic) and Δt ∝ 1/√Y (\`zip = stiffness gamma_n dt\`), and the onset"
	echo "of convection without intruder is searched as in claim 1 (flux ≥ 2 particles/period"
	echo "through 0.4–0.6 of the bed, bisection per replicate)."
	echo
	A=$(q "SELECT DISTINCT amplitude FROM runs WHERE campaign = '$n' AND current LIMIT 1"); A=${A:-2}
	G=$(q "SELECT DISTINCT gravity FROM runs WHERE campaign = '$n' AND current LIMIT 1"); G=${G:-981}
	rows=$(onset_rows "$n")
	if [ -z "$rows" ]; then echo "*Not run yet.*"; echo; return; fi
	echo "The bed's lowest elastic frequency f_el is an estimate, not a measurement: a column of"
	echo "N = n_grains · 2r̄ / width rows of grains of mass m = 2πρr̄², each on two below it at ±30°"
	echo "(vertical stiffness 1.5 Y), fixed at the floor and free at the top:"
	echo "f_el = (1/π) √(1.5 Y/m) sin(π / (2(2N + 1)))."
	echo
	echo "| Y (g/s²) | γ_N (1/s) | Δt (s) | onset f (Hz), 95 % interval | onset Γ | replicates (runs) | below / above the range | f_el (Hz) | drive / f_el at onset |"
	echo "|---|---|---|---|---|---|---|---|---|"
	: >"$ANA/q1_stiffness.dat"
	local grp est lo hi rep runs found below above state Y gn dt fel
	while IFS=$'\t' read -r grp est lo hi rep runs found below above state; do
		Y=$(grp_get "$grp" stiffness) gn=$(grp_get "$grp" gamma_n) dt=$(grp_get "$grp" dt)
		fel=$(q "SELECT printf('%.3g', (1 / 3.141592653589793) * sqrt(1.5 * $Y / (mass_factor * density * 0.25 * (r_min + r_max) * (r_min + r_max)))
			 * sin(3.141592653589793 / (2 * (2 * n_grains * (r_min + r_max) / width + 1))))
			 FROM runs WHERE campaign = '$n' AND stiffness = $Y LIMIT 1")
		local ftxt
		ftxt=$(iv "$est $lo $hi")
		[ "$est" = - ] && [ "${above:-0}" -gt 0 ] && ftxt="above the range for $above of $rep replicates; from $lo"
		[ "$est" = - ] && [ "${below:-0}" -gt 0 ] && ftxt="below the range for $below of $rep replicates; up to $hi"
		printf '| %s | %s | %s | %s | %s [%s, %s] | %s (%s) | %s / %s | %s | %s |\n' "$Y" "$gn" "$dt" "$ftxt" \
			"$(gam "$est" "$A" "$G")" "$(gam "$lo" "$A" "$G")" "$(gam "$hi" "$A" "$G")" "$rep" "$runs" "$below" "$above" \
			"${fel:--}" "$(awk -v f="$est" -v e="${fel:-x}" 'BEGIN { if (f + 0 == f && e + 0 == e && e > 0) printf "%.2f", f / e; else print "-" }')"
		echo "$Y $est $lo $hi $(gam "$est" "$A" "$G") $(gam "$lo" "$A" "$G") $(gam "$hi" "$A" "$G") ${fel:-nan}" >>"$ANA/q1_stiffness.dat"
	done <<<"$rows"
	echo
	echo "Runs: $(counts "$n")."
	echo
	gpfig "$ANA/q1_stiffness" <<EOF
set logscale x; set xlabel 'contact stiffness Y (g/s^2)'; set ylabel 'onset {/Symbol G} = A(2{/Symbol p}f)^2/g'
set grid; set yrange [0:1.8]; set xrange [1e6:1e9]
set key bottom right box opaque; set datafile missing '-'
# column 5: the onset's Gamma (missing above the searched range), 6 and 7 its interval
# (7 missing when some replicates lay above the range: the bar then ends at the point)
plot '$ANA/q1_stiffness.dat' u 1:5:6:(\$7 == \$7 ? \$7 : \$5) w yerrorbars lw 2 pt 7 ps 1.3 lc rgb '#9400d3' t 'onset of convection (95 % interval)', \
     '' u 1:(\$5 == \$5 ? 1/0 : \$6) w p pt 9 ps 2 lc rgb '#9400d3' t 'onset above the searched range: its lower bound', \
     1 w l dt 2 lw 2 lc rgb '#009e73' t '{/Symbol G} = 1'
EOF
	# the answer, by rule, once every search is done: yes when the stiffest bed's onset
	# interval lies at Gamma >= 1; in part when it lies above the softest bed's interval;
	# else no. An onset above the searched range counts with its lower bound.
	local ndone ngrp
	read -r ndone ngrp <<<"$(q "SELECT SUM(state = 'done'), COUNT(*) FROM onset_group WHERE campaign = '$n'" | tr '\t' ' ')"
	local first last
	first=$(head -1 "$ANA/q1_stiffness.dat") last=$(tail -1 "$ANA/q1_stiffness.dat")
	set -- $first; local y0=${1:-} g0=${5:-} g0hi=${7:-} ratio0
	ratio0=$(awk -v f="${2:-x}" -v e="${8:-x}" 'BEGIN { if (f + 0 == f && e + 0 == e && f > 0) printf "%.1f", e / f; else print "?" }')
	set -- $last; local g1=${5:-} g1lo=${6:-} y1=${1:-}
	local ans
	ans=$(awk -v a="${g0hi:-x}" -v b="${g1lo:-x}" 'BEGIN { if (!(a + 0 == a && b + 0 == b)) print "none";
		else if (b >= 1) print "hard"; else if (b > a) print "part"; else print "no" }')
	[ "${ndone:-0}" = "${ngrp:-x}" ] || ans=running
	case $ans in
	running) echo "**Answer: not yet.** ${ndone:-0} of ${ngrp:-0} searches are done; \`make reproduce\` resumes them." ;;
	hard) echo "**Answer: yes.** At Y = $y1 g/s² the onset lies at Γ ≥ 1 ($([ "$g1" = - ] && echo "above the searched range: its interval starts at Γ = $g1lo" || echo "Γ = $g1, interval from $g1lo")), at the paper's Y = $y0 at Γ = $g0 (up to $g0hi): with stiffer contacts at the same restitution the bed convects only above Γ = 1, as experiments and hard-contact simulations do. The convection below Γ = 1 is an effect of the soft contacts: at the paper's Y the bed's estimated lowest elastic frequency is only $ratio0 times the drive's at the onset." ;;
	part) echo "**Answer: in part.** The onset rises with the stiffness (Γ = $g0 at the paper's Y, $g1 at Y = $y1; the intervals separate) but stays below Γ = 1." ;;
	no) echo "**Answer: no, not in this range.** The onset at Y = $y1 (Γ = $g1) is not above the paper's (Γ = $g0) beyond the intervals: convection below Γ = 1 is not a matter of the contact stiffness between $y0 and $y1 g/s² at a fixed restitution." ;;
	*) echo "**Answer: none** (the searches found no onset to compare)." ;;
	esac
	echo
	echo "$(fig "$ANA/q1_stiffness.png" q1_stiffness.png)"
	echo
}

q_width() {
	local n=${QNAME[q2_width_onset]} r=${QNAME[q2_width_rise]} rows
	echo "## Open question 2: the box width"
	echo
	integrator "${QNAME[q2_width_onset]}" "${QFILE[q2_width_onset]}"
	integrator "${QNAME[q2_width_rise]}" "${QFILE[q2_width_rise]}"
	echo
	echo "The paper does not give its box width; ours is 60 cm, a bed about as high as wide. Widths from"
	echo "40 to 160 cm at a fixed bed height (\`zip = width n_grains\`, 950 grains per 60 cm): the onset of"
	echo "convection without intruder (searched as in claim 1), and the rise of 𝓡 = 4 placed one row"
	echo "above the floor in the middle of the box at 3.2 Hz within 180 s."
	echo
	rows=$(onset_rows "$n")
	echo "| width (cm) | grains | onset f (Hz), 95 % interval | replicates (runs) | below / above | runs with 𝓡 = 4 | risen | fraction risen | median wait |"
	echo "|---|---|---|---|---|---|---|---|---|"
	local grp est lo hi rep runs found below above state wd ng w
	while IFS=$'\t' read -r grp est lo hi rep runs found below above state; do
		[ -n "$grp" ] || continue
		wd=$(grp_get "$grp" width) ng=$(grp_get "$grp" n_grains)
		w="width = $wd"
		printf '| %s | %s | %s | %s (%s) | %s / %s | %s | %s | %s | %s s |\n' "$wd" "$ng" "$(iv "$est $lo $hi")" "$rep" "$runs" \
			"$below" "$above" "$(val "$r" waiting runs "$w" | cut -f1)" "$(val "$r" waiting risen "$w" | cut -f1)" \
			"$(iv "$(val "$r" waiting fraction_risen "$w")")" "$(iv "$(val "$r" waiting median "$w")")"
	done <<<"$rows"
	[ -n "$rows" ] || echo "| *not run yet* | | | | | | | | |"
	echo
	local lr sep
	lr=$(q "SELECT printf('%.3g', value) FROM analysis WHERE campaign = '$r' AND tool = 'waiting' AND key = 'logrank_p' LIMIT 1")
	echo "Log-rank test of equal waiting times across the widths: p = ${lr:-not computed}."
	# do the onsets depend on the width: two widths whose intervals do not overlap
	sep=$(q "SELECT GROUP_CONCAT(a.grp || ' vs ' || b.grp, '; ') FROM onset_group a JOIN onset_group b
		 ON a.campaign = b.campaign AND a.point < b.point
		 WHERE a.campaign = '$n' AND a.state = 'done' AND b.state = 'done' AND (a.ci_hi < b.ci_lo OR b.ci_hi < a.ci_lo)")
	local nd ng
	read -r nd ng <<<"$(q "SELECT SUM(state = 'done'), COUNT(*) FROM onset_group WHERE campaign = '$n'" | tr '\t' ' ')"
	echo
	if [ "${nd:-0}" != "${ng:-x}" ]; then echo "**Answer: not yet** (${nd:-0} of ${ng:-0} onset searches done)."
	elif [ -n "$sep" ]; then echo "**Answer: the onset depends on the width**: the intervals separate for $sep."
	else echo "**Answer: the onset does not depend on the width** between 40 and 160 cm within the intervals (every pair overlaps)."; fi
	echo "The rise: the log-rank p above tests equal waiting-time distributions across the widths."
	echo "Runs: onset $(counts "$n"); rise $(counts "$r")."
	echo
	echo "$(fig "$ANA/$r/waiting_km.png" q2_width_km.png)"
	echo
}

q_periodic() {
	local n=${QNAME[q3_periodic]} csv
	csv=$ANA/$n/onset_runs.csv
	echo "## Open question 3: periodic side boundaries"
	echo
	integrator "${QNAME[q3_periodic]}" "${QFILE[q3_periodic]}"
	echo
	echo "Without side walls (\`sides = periodic\`: the bottom row closes on itself and grains cross"
	echo "x = 0 / x = W), does the bed still convect? No intruder. Three measures per run, means over"
	echo "replicates with 95 % Student-t intervals:"
	echo
	echo "- the persistent flow P (bin/convect): from the displacement field averaged over blocks of"
	echo "  10 periods, P² = the mean over neighbouring blocks of the product of their vertical"
	echo "  displacements, cell by cell, in 0.3–0.7 of the bed. The sampling noise of two blocks is"
	echo "  independent and averages out; a roll that outlives a block stays. It does not depend on"
	echo "  where the rolls sit. A bed convects when P's interval lies above 0."
	echo "- the roll strength S: the rms of the same vertical displacements block by block; it"
	echo "  carries the sampling noise too, so it is > 0 without rolls and grows with the agitation;"
	echo "- the flux Φ through 0.4–0.6 of the bed (claim 1's, bin/onset): it counts upward crossings"
	echo "  near the box centre against those near the sides, so without walls, where nothing pins"
	echo "  the rolls, its sign depends on where they settle."
	echo
	if [ ! -f "$csv" ] && [ -z "$(val "$n" convect strength "sides = 'walls'")" ]; then echo "*Not run yet.*"; echo; return; fi
	echo "| frequency | P with walls (cm/period) | P periodic | S with walls | S periodic | Φ with walls | Φ periodic | runs |"
	echo "|---|---|---|---|---|---|---|---|"
	local f a b wm wl wh wn pm pl ph pn conv_w="" conv_p="" s lo
	for f in $(q "SELECT DISTINCT frequency FROM runs WHERE campaign = '$n' AND current ORDER BY frequency"); do
		a=$(csv_mean "$csv" phi "sides=walls frequency=$f") b=$(csv_mean "$csv" phi "sides=periodic frequency=$f")
		set -- $a; wm=$1 wl=$2 wh=$3 wn=$4
		set -- $b; pm=$1 pl=$2 ph=$3 pn=$4
		printf '| %s Hz | %s | %s | %s | %s | %s [%s, %s] | %s [%s, %s] | %s + %s |\n' "$f" \
			"$(iv "$(val "$n" convect persistent "sides = 'walls' AND frequency = $f")")" \
			"$(iv "$(val "$n" convect persistent "sides = 'periodic' AND frequency = $f")")" \
			"$(iv "$(val "$n" convect strength "sides = 'walls' AND frequency = $f")")" \
			"$(iv "$(val "$n" convect strength "sides = 'periodic' AND frequency = $f")")" \
			"$wm" "$wl" "$wh" "$pm" "$pl" "$ph" "$wn" "$pn"
		# the rule: a bed convects at f when the lower bound of its C (P squared) is above 0
		for s in walls periodic; do
			read -r _ lo _ _ <<<"$(val "$n" convect persistence_c "sides = '$s' AND frequency = $f")"
			if awk -v l="${lo:-x}" 'BEGIN { exit !(l + 0 == l && l > 0) }'; then
				[ $s = walls ] && conv_w="$conv_w $f" || conv_p="$conv_p $f"
			fi
		done
	done
	echo
	echo "Runs: $(counts "$n")."
	echo
	if [ -n "$conv_p" ]; then echo "**Answer: yes.** Without side walls the bed has a persistent flow (P's interval above 0) at${conv_p} Hz; with walls at${conv_w:- no frequency}."
	elif [ -n "$conv_w" ]; then echo "**Answer: no.** With walls the bed convects steadily at${conv_w} Hz (P's interval above 0); without walls at no frequency here: in this model the side walls drive the rolls."
	else echo "**Answer: none.** Neither bed has a persistent flow beyond its interval at these frequencies."; fi
	echo
	echo "$(fig "$ANA/$n/convect.png" q3_periodic_strength.png) $(fig "$ANA/$n/onset.png" q3_periodic_flux.png)"
	echo
}

q_large() {
	local n=${QNAME[q4_large]} r w lr
	echo "## Open question 4: large intruders"
	echo
	integrator "${QNAME[q4_large]}" "${QFILE[q4_large]}"
	echo
	echo "𝓡 from 4 to 12 at 3.2 Hz, one row above the floor, within 180 s (the literature predicts a"
	echo "critical size ratio above which the intruder always rises)."
	echo
	echo "| 𝓡 | runs | risen | fraction risen | median wait (one diameter) | median wait (half way) |"
	echo "|---|---|---|---|---|---|"
	for r in $(q "SELECT DISTINCT radius_ratio FROM runs WHERE campaign = '$n' AND current ORDER BY radius_ratio"); do
		w="radius_ratio = $r"
		printf '| %s | %s | %s | %s | %s s | %s s |\n' "$r" "$(val "$n" waiting runs "$w" | cut -f1)" \
			"$(val "$n" waiting risen "$w" | cut -f1)" "$(iv "$(val "$n" waiting fraction_risen "$w")")" \
			"$(iv "$(val "$n" waiting median "$w")")" "$(iv "$(val "$n" waiting way_median "$w")")"
	done
	echo
	lr=$(q "SELECT printf('%.3g', value) FROM analysis WHERE campaign = '$n' AND tool = 'waiting' AND key = 'logrank_p' LIMIT 1")
	echo "Log-rank test of equal waiting times across 𝓡: p = ${lr:-not computed}. Runs: $(counts "$n")."
	echo
	# the answer: a critical size ratio shows as an R below which some intruders stay down
	# and above which all rise
	local notall allr
	notall=$(q "SELECT GROUP_CONCAT(radius_ratio, ', ') FROM analysis WHERE campaign = '$n' AND tool = 'waiting'
		    AND key = 'fraction_risen' AND value < 1")
	allr=$(q "SELECT MIN(radius_ratio) || '–' || MAX(radius_ratio) FROM analysis WHERE campaign = '$n' AND tool = 'waiting'
		  AND key = 'fraction_risen' AND value = 1")
	if [ -z "$notall" ] && [ -n "$allr" ]; then
		echo "**Answer: no critical size ratio in this range.** Every intruder of 𝓡 = $allr rose within the run at 3.2 Hz; the waits $(awk -v p="${lr:-1}" 'BEGIN { print (p + 0 == p && p < 0.05) ? "differ across 𝓡 (log-rank p < 0.05)" : "do not differ across 𝓡 beyond chance (log-rank p ≥ 0.05)" }')."
	else
		echo "**Answer:** not every intruder rose at 𝓡 = ${notall:-?}; all did at 𝓡 = ${allr:-none}."
	fi
	echo
	echo "$(fig "$ANA/$n/waiting_km.png" q4_large_km.png)"
	echo
}

q_long() {
	local n=${QNAME[q5_long]} r w
	echo "## Open question 5: long times, the whale oscillation"
	echo
	integrator "${QNAME[q5_long]}" "${QFILE[q5_long]}"
	echo
	echo "600 s at 3.2 Hz for 𝓡 = 2 … 8: after its rise the intruder dives into the bed and comes back"
	echo "(bin/whale, definitions in analysis/README.md: the height averaged over each drive period, from"
	echo "20 s after the rise; a dive starts below the top level (90th percentile) minus one intruder"
	echo "radius and ends back above half that; period = mean time between dive starts, depth = top"
	echo "level − lowest point of a dive; means over runs with bootstrap 95 % intervals)."
	echo
	echo "| 𝓡 | runs | risen | with a period (≥ 2 dives) | period (s) | spectral period (s) | dive depth (cm) | dives per minute |"
	echo "|---|---|---|---|---|---|---|---|"
	for r in $(q "SELECT DISTINCT radius_ratio FROM runs WHERE campaign = '$n' AND current ORDER BY radius_ratio"); do
		w="radius_ratio = $r"
		printf '| %s | %s | %s | %s | %s | %s | %s | %s |\n' "$r" "$(val "$n" whale runs "$w" | cut -f1)" \
			"$(val "$n" whale risen "$w" | cut -f1)" "$(val "$n" whale with_period "$w" | cut -f1)" \
			"$(iv "$(val "$n" whale period "$w")")" "$(iv "$(val "$n" whale spec_period "$w")")" \
			"$(iv "$(val "$n" whale depth "$w")")" "$(iv "$(val "$n" whale rate "$w")")"
	done
	echo
	local tp td
	tp=$(q "SELECT printf('%.2f', value) || ' (p = ' || (SELECT printf('%.3g', value) FROM analysis WHERE campaign = '$n'
		AND tool = 'whale' AND key = 'trend_period_p' LIMIT 1) || ', ' || n || ' runs)' FROM analysis
		WHERE campaign = '$n' AND tool = 'whale' AND key = 'trend_period_rho' LIMIT 1")
	td=$(q "SELECT printf('%.2f', value) || ' (p = ' || (SELECT printf('%.3g', value) FROM analysis WHERE campaign = '$n'
		AND tool = 'whale' AND key = 'trend_depth_p' LIMIT 1) || ', ' || n || ' runs)' FROM analysis
		WHERE campaign = '$n' AND tool = 'whale' AND key = 'trend_depth_rho' LIMIT 1")
	echo "Trend with 𝓡, Spearman's rank correlation over runs (permutation p): period ${tp:-not computed}; depth ${td:-not computed}."
	echo "Runs: $(counts "$n")."
	echo
	# the answer: a trend is one whose permutation p is below 0.05, its sign the rho's
	trend() { # KEY WORD
		local rho p
		read -r rho p <<<"$(q "SELECT a.value, b.value FROM analysis a JOIN analysis b ON a.campaign = b.campaign AND a.tool = b.tool
			AND a.grp = b.grp WHERE a.campaign = '$n' AND a.tool = 'whale' AND a.key = 'trend_$1_rho' AND b.key = 'trend_$1_p' LIMIT 1" | tr '\t' ' ')"
		awk -v r="${rho:-x}" -v p="${p:-x}" -v w="$2" 'BEGIN { if (!(r + 0 == r && p + 0 == p)) print "the " w " has no trend computed";
			else if (p >= 0.05) print "the " w " shows no trend with 𝓡 beyond chance";
			else print "the " w (r < 0 ? " decreases" : " increases") " with 𝓡" }'
	}
	local nr np
	read -r nr np <<<"$(q "SELECT CAST(SUM(CASE WHEN key = 'risen' THEN value END) AS INTEGER),
		CAST(SUM(CASE WHEN key = 'with_period' THEN value END) AS INTEGER)
		FROM analysis WHERE campaign = '$n' AND tool = 'whale'" | tr '\t' ' ')"
	echo "**Answer:** ${np:-?} of the ${nr:-?} runs whose intruder rose dived at least twice after it; $(trend depth "dives' depth"), and $(trend period "period")."
	echo
	echo "$(fig "$ANA/$n/whale.png" q5_whale.png)"
	echo
}

questions_report() {
	qwant 1 && q_stiffness
	qwant 2 && q_width
	qwant 3 && q_periodic
	qwant 4 && q_large
	qwant 5 && q_long
	return 0
}
