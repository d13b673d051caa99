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
for c in q1_stiffness q2_width_onset q2_width_rise q3_periodic q4_large q5_long q6_law_onset q6_law_rise; do
	QFILE[$c]=$(campaign "$c.campaign")
	QNAME[$c]=$(cname "${QFILE[$c]}")
done
qwant() { case " $QUESTIONS " in *" $1 "*) return 0 ;; esac; return 1; }
campaigns_of_question() {
	case $1 in
	1) echo q1_stiffness ;; 2) echo q2_width_onset q2_width_rise ;; 3) echo q3_periodic ;;
	4) echo q4_large ;; 5) echo q5_long ;; 6) echo q6_law_onset q6_law_rise ;;
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
	qwant 6 && { tool onset "${QNAME[q6_law_onset]}" --axis gamma; tool waiting "${QNAME[q6_law_rise]}"; }
	return 0
}

# onset_rows CAMPAIGN -> per [onset] group: grp estimate lo hi replicates runs found below above state
onset_rows() {
	q "SELECT grp, $(num estimate), $(num ci_lo), $(num ci_hi), replicates, runs, found, below, above, state
	   FROM onset_group WHERE campaign = '$1' ORDER BY point"
}
# key=value out of an onset group's label ("stiffness=3000000 gamma_n=100 dt=0.0002")
grp_get() { tr ' ' '\n' <<<"$1" | awk -F= -v k="$2" '$1 == k { print $2 }'; }
# Gamma of a frequency (A, g of the paper's scene): drive_gamma's formula (core/model/drive.h;
# docs/model.md, "Units and the paper's values"), restated because awk cannot call it
gam() { awk -v f="$1" -v a="$2" -v g="$3" 'BEGIN { if (f + 0 == f) printf "%.3g", a * (6.283185307179586 * f) * (6.283185307179586 * f) / g; else print "-" }'; }
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
	# the answer, by the rule of scripts/verdicts.sh, once every search is done
	local ndone ngrp
	read -r ndone ngrp <<<"$(q "SELECT SUM(state = 'done'), COUNT(*) FROM onset_group WHERE campaign = '$n'" | tr '\t' ' ')"
	answer_q1 "$ANA/q1_stiffness.dat" "${ndone:-0}" "${ngrp:-0}" | answer_md
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
	local lr
	lr=$(q "SELECT printf('%.3g', value) FROM analysis WHERE campaign = '$r' AND tool = 'waiting' AND key = 'logrank_p' LIMIT 1")
	echo "Log-rank test of equal waiting times across the widths: p = ${lr:-not computed}."
	echo
	answer_q2 "$n" | answer_md
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
	local f a b wm wl wh wn pm pl ph pn
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
	done
	echo
	echo "Runs: $(counts "$n")."
	echo
	answer_q3 "$n" | answer_md
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
	answer_q4 "$n" | answer_md
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
	echo "(bin/whale, definitions in docs/analysis.md: the height averaged over each drive period, from"
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
	answer_q5 "$n" | answer_md
	echo
	echo "$(fig "$ANA/$n/whale.png" q5_whale.png)"
	echo
}

q_law() {
	local n=${QNAME[q6_law_onset]} r=${QNAME[q6_law_rise]} row
	echo "## Open question 6: a realistic contact law (the referee's question)"
	echo
	integrator "$n" "${QFILE[q6_law_onset]}"
	integrator "$r" "${QFILE[q6_law_rise]}"
	echo
	echo "The paper's contacts are soft linear springs without shear history (open question 1). With"
	echo "Hertz's normal force (\`normal = hertz\`), Cundall–Strack's shear spring with history"
	echo "(\`tangential = spring\`), a restitution of 0.9 for a mean grain pair at 20 cm/s and μ = 0.5"
	echo "(docs/model.md, \"Normal law\", \"Tangential law\"; the damping that gives it in the campaign"
	echo "file): where is the onset of convection in Γ (claim 1's definition, searched in Γ), and does"
	echo "the intruder (𝓡 = 4, one row deep) still rise at the paper's Γ = 0.82 (3.2 Hz) within 60 s?"
	echo "The rule: the onset is below (above) Γ = 1 when its interval lies below (above) 1; the"
	echo "intruder still rises when the Clopper–Pearson interval of the fraction risen lies above 1/2,"
	echo "no longer when it lies below; else undecided."
	echo
	row=$(q "SELECT $(num estimate) || ' [' || $(num ci_lo) || ', ' || $(num ci_hi) || '], ' || replicates || ' replicates, '
		|| runs || ' runs (' || state || ')' FROM onset_group WHERE campaign = '$n' ORDER BY point LIMIT 1")
	echo "| | value |"
	echo "|---|---|"
	echo "| onset of convection (Γ, the search's median of the replicates' onsets) | ${row:-not run yet} |"
	echo "| fraction risen at Γ = 0.82 within 60 s | $(iv "$(val "$r" waiting fraction_risen)") ($(val "$r" waiting risen | cut -f1) of $(val "$r" waiting runs | cut -f1) beds) |"
	echo "| median waiting time (one diameter) | $(iv "$(val "$r" waiting median)") s |"
	echo
	echo "Runs: onset $(counts "$n"); rise $(counts "$r")."
	echo
	answer_q6 "$n" "$r" | answer_md
	echo
	echo "$(fig "$ANA/$n/onset.png" q6_law_onset.png) $(fig "$ANA/$r/waiting_km.png" q6_law_km.png)"
	echo
}

questions_report() {
	qwant 1 && q_stiffness
	qwant 2 && q_width
	qwant 3 && q_periodic
	qwant 4 && q_large
	qwant 5 && q_long
	qwant 6 && q_law
	return 0
}
