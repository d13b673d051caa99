#!/usr/bin/env bash
# hdf5_params.sh - the HDF5 output records the run: every scene parameter of
# `shake --params` is an attribute of /parameters of the right type whose value equals
# the input (reals exactly, compared at %.17g), /provenance is complete, status is ok,
# the file follows H5MD 1.1 (/h5md, particle groups with box, step/time/value elements,
# units), and the datasets and the XDMF sidecar have the shapes the run implies.
# tier: slow: a run for every observable switch
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1

"$SHAKE" --params >params.tsv 2>/dev/null
if [ "$(head -n 1 params.tsv | cut -f1,2,4)" != "$(printf 'name\ttype\tdefault')" ] || [ "$(wc -l <params.tsv)" -lt 30 ]; then
	fail params.table "shake --params does not give the name/type/unit/default TSV"
	finish
fi
ok params.table

# expected value of every parameter: the default, overridden by what the run was given
# expect_params TSV KEY=VALUE... > name<TAB>type<TAB>expected
expect_params() {
	local tsv=$1
	shift
	printf '%s\n' "$@" | awk -F'\t' -v OFS='\t' '
		FNR == NR { i = index($0, "="); set[substr($0, 1, i - 1)] = substr($0, i + 1); next }
		FNR == 1 { next }
		{ v = ($1 in set) ? set[$1] : $4; print $1, $2, v }' - "$tsv"
}

# compare_params ID FILE KEY=VALUE... : one check per parameter
compare_params() {
	local id=$1 f=$2
	shift 2
	local name type want got dt
	while IFS=$'\t' read -r name type want; do
		got=$(attr "$f" "/parameters/$name")
		dt=$(attrtype "$f" "/parameters/$name")
		case "$type" in
		real)
			# a pair class's `same` (docs/model.md, "Materials per pair of kinds") is -1 in the file
			[ "$want" = same ] && want=-1
			want=$(awk -v x="$want" 'BEGIN { printf "%.17g", x + 0 }')
			got=$(awk -v x="$got" 'BEGIN { if (x == "") print ""; else printf "%.17g", x + 0 }')
			[ "$dt" = H5T_IEEE_F64LE ] || { fail "$id.$name" "type $dt, expected H5T_IEEE_F64LE"; continue; } ;;
		int) [ "$dt" = H5T_STD_I64LE ] || { fail "$id.$name" "type $dt, expected H5T_STD_I64LE"; continue; } ;;
		*) [ "$dt" = H5T_STRING ] || { fail "$id.$name" "type $dt, expected H5T_STRING"; continue; } ;;
		esac
		if [ "$got" = "$want" ]; then ok "$id.$name"; else fail "$id.$name" "file has '$got', input was '$want'"; fi
	done < <(expect_params params.tsv "$@")
}

# --- run 1: placement and settling, many non-default values of every type ---
tiny_bed width=20.5
RUN1=("${BEDARGS[@]}" settle_max=12.5
	settle=yes settle_drag=21.3 r_min=0.9 r_max=1.1 seed=12345 density=1.1 mass_factor=6.3
	wall_radius=0.95 wall_spacing=1.9 gamma_s=2.7 gamma_n=99.9 mu=0.45 gravity=980.665
	stiffness=3.1e6 clip_attractive=yes wall_mass=infinite integrator=verlet dt=4e-05
	skin=0.2 max_overlap=0.35 frequency=4 amplitude=1.1 duration=1 traj_rate=200 snapshots=yes energy_rate=1000
	checkpoint_every=0 checkpoint="$TMP/my.ckpt" restart=no write_particles="$TMP/p1.txt"
	write_lammps="$TMP/p1.data" progress=no output="$TMP/out1.h5")
log=$TMP/run1.log
shake_run "$log" "${RUN1[@]}"
rc=$?
if [ "$rc" -ne 0 ] || [ ! -s out1.h5 ]; then
	fail run1 "exit $rc: $(head -c 300 "$log")"
	finish
fi
ok run1
compare_params run1.param out1.h5 "${RUN1[@]}"

# --- run 2: from the particle file, other non-defaults (no recording) ---
# (p1.txt's disks weigh what run 1's density and mass_factor made them: the file's masses)
RUN2=(particles="$TMP/p1.txt" particle_mass=file settle=no integrator=gear4 dt=5e-05 duration=0.05 wall_height=30.5
	snapshots=no traj_rate=0 wall_mass=disk clip_attractive=no mu=0.6 frequency=2.7
	amplitude=0.5 output="$TMP/out2.h5" progress=yes restart=auto)
shake_run "$TMP/run2.log" "${RUN2[@]}"
rc=$?
if [ "$rc" -ne 0 ] || [ ! -s out2.h5 ]; then
	fail run2 "exit $rc: $(head -c 300 "$TMP/run2.log")"
else
	ok run2
	# radius_ratio is the file's, not the key's default: p1.txt's intruder of run 1's R = 2 cm
	# over the mean grain radius 1 cm (docs/model.md, "Units and the paper's values")
	compare_params run2.param out2.h5 "${RUN2[@]}" radius_ratio=2
	d=$(dims out2.h5 /particles/bed/position/value)
	[ -z "$d" ] && ok run2.no_snapshots || fail run2.no_snapshots "/particles/bed/position/value is [$d] with snapshots=no"
	d=$(dims out2.h5 /particles/intruder/position/value)
	[ "$d" = "0 1 2" ] && ok run2.no_trajectory || fail run2.no_trajectory "/particles/intruder/position/value is [$d] with traj_rate=0"
fi

# --- status and provenance of run 1 ---
f=out1.h5
[ "$(attr $f /status)" = ok ] && ok status.ok || fail status.ok "status = '$(attr $f /status)'"
[ "$(attr $f /exit_code)" = 0 ] && ok status.exit_code || fail status.exit_code "exit_code = '$(attr $f /exit_code)'"
[ "$(attr $f /format)" = "$(sed -n 's/^#define H5ID_FORMAT "\(.*\)"$/\1/p' "$REPO/core/io/h5id.h")" ] && ok format || fail format "format = '$(attr $f /format)'"
for a in git_hash compiler host start_time end_time; do
	v=$(attr $f /provenance/$a)
	[ -n "$v" ] && ok "provenance.$a" || fail "provenance.$a" "/provenance/$a missing or empty"
done
gh=$(attr $f /provenance/git_hash)
[[ "$gh" =~ ^[0-9a-f]{7,40}$ ]] && ok provenance.git_hash_form || fail provenance.git_hash_form "git_hash '$gh' is not a commit hash"
st=$(attr $f /provenance/start_time) en=$(attr $f /provenance/end_time)
[[ "$st" =~ ^[0-9]{4}-[0-9]{2}-[0-9]{2}T ]] && [[ ! "$en" < "$st" ]] && ok provenance.times ||
	fail provenance.times "start_time '$st', end_time '$en'"

# --- shapes of run 1: duration 1 s, f = 4 Hz -> 4 periods -> K = 5; 200 Hz -> 201 rows ---
nm=$(attr $f /n_mobile)
nw=$(attr $f /n_walls)
[ "$nm" = 61 ] && ok shape.n_mobile || fail shape.n_mobile "n_mobile = '$nm', expected 60 grains + 1 intruder"
[ -n "$nw" ] && [ "$nw" -gt 0 ] && ok shape.n_walls || fail shape.n_walls "n_walls = '$nw'"
B=/particles/bed
d=$(dims $f /particles/intruder/position/value)
[ "$d" = "201 1 2" ] && ok shape.trajectory || fail shape.trajectory "/particles/intruder/position/value is [$d], expected [201 1 2]"
for e in position velocity; do
	d=$(dims $f $B/$e/value)
	[ "$d" = "5 $nm 2" ] && ok "shape.bed_$e" || fail "shape.bed_$e" "$B/$e/value is [$d], expected [5 $nm 2]"
done
d=$(dims $f $B/angle/value)
[ "$d" = "5 $nm" ] && ok shape.bed_angle || fail shape.bed_angle "$B/angle/value is [$d]"
d=$(dims $f $B/position/time)
[ "$d" = 5 ] && ok shape.snapshot_time || fail shape.snapshot_time "$B/position/time is [$d], expected [5]"
for c in x y vx vy omega theta; do
	d=$(dims $f /final/$c)
	[ "$d" = "$((nm + nw))" ] && ok "shape.final_$c" || fail "shape.final_$c" "/final/$c is [$d], expected [$((nm + nw))]"
done
for c in id species radius mass; do
	d=$(dims $f $B/$c) dw=$(dims $f /particles/walls/$c) df=$(dims $f /final/$c)
	[ "$d" = "$nm" ] && [ "$dw" = "$nw" ] && [ "$df" = "$((nm + nw))" ] && ok "shape.particles_$c" ||
		fail "shape.particles_$c" "$B/$c is [$d], /particles/walls/$c [$dw], /final/$c [$df]"
done
[ "$(dims $f /particles/walls/position)" = "$nw 2" ] && ok shape.walls_position || fail shape.walls_position "[$(dims $f /particles/walls/position)]"
[ "$(h5vals $f $B/species | grep -c '^2$')" = 0 ] && [ "$(h5vals $f /particles/walls/species | grep -c '^2$')" = "$nw" ] &&
	[ "$(h5vals $f /final/species | tr '\n' ' ')" = "$({ h5vals $f $B/species; h5vals $f /particles/walls/species; } | tr '\n' ' ')" ] &&
	ok particles.species_by_group || fail particles.species_by_group "walls in the bed, or /final's species are not the bed's then the walls'"
# snapshot times are k / f (to within one step); trajectory rows run from t = 0 to duration
h5vals $f $B/position/time >times.txt
awk '{ if ($1 < 0.25 * (NR - 1) - 1e-12 || $1 > 0.25 * (NR - 1) + 4e-5 + 1e-12) bad = 1 } END { exit bad || NR != 5 }' times.txt &&
	ok shape.snapshot_times || fail shape.snapshot_times "$B/position/time = $(tr '\n' ' ' <times.txt), expected 0 0.25 0.5 0.75 1"
# H5MD: step is the engine step of each time (dt = 4e-5)
paste -d' ' times.txt <(h5vals $f $B/position/step) | awk '{ if ($2 != int($1 / 4e-5 + 0.5)) bad = 1 } END { exit bad || NR != 5 }' &&
	ok h5md.step_is_time_over_dt || fail h5md.step_is_time_over_dt "steps $(h5vals $f $B/position/step | tr '\n' ' ')"
h5traj $f | awk '{ print $1 }' >traj_t.txt
awk 'NR == 1 && $1 != 0 { bad = 1 } { if ($1 < (NR - 1) * 0.005 - 1e-12 || $1 > (NR - 1) * 0.005 + 4e-5) bad = 1; last = $1 }
	END { exit bad || NR != 201 || last != 1 }' traj_t.txt && ok shape.trajectory_times ||
	fail shape.trajectory_times "trajectory t column is not 0, 0.005, ..., 1 ($(head -n 3 traj_t.txt | tr '\n' ' ')... $(tail -n 1 traj_t.txt))"

# --- H5MD 1.1 conventions ---
[ "$(h5dump -a /h5md/version $f 2>/dev/null | awk '/\(0\)/ { sub(/.*\(0\): */, ""); print; exit }')" = "1, 1" ] &&
	ok h5md.version || fail h5md.version "/h5md version is not 1, 1"
[ "$(attr $f /h5md/creator/name)" = shakebox ] && [ -n "$(attr $f /h5md/author/name)" ] && ok h5md.creator_author ||
	fail h5md.creator_author "creator '$(attr $f /h5md/creator/name)', author '$(attr $f /h5md/author/name)'"
[ "$(attr $f $B/box/dimension)" = 2 ] && h5dump -a $B/box/boundary $f | grep -q '"none", "none"' && ok h5md.box ||
	fail h5md.box "dimension '$(attr $f $B/box/dimension)', boundary $(h5dump -a $B/box/boundary $f | grep '(0)')"
[ "$(dims $f $B/box/offset/value)" = "5 2" ] && [ "$(dims $f $B/box/offset_velocity/value)" = "5 2" ] && ok h5md.box_offset || fail h5md.box_offset "$B/box/offset/value is [$(dims $f $B/box/offset/value)]"
units_ok=1
for u in "$B/position/value cm" "$B/velocity/value cm s-1" "$B/position/time s" "$B/angle/value rad" "$B/mass g" \
	"$B/radius cm" "/particles/intruder/velocity/value cm s-1" "/final/vx cm s-1" "$B/box/edges cm"; do
	set -- $u
	got=$(attr $f "$1/unit")
	[ "$got" = "${u#* }" ] || { units_ok=0; echo "# $1: unit '$got', expected '${u#* }'"; }
done
[ $units_ok = 1 ] && ok h5md.units || fail h5md.units "a unit attribute is missing or wrong (see above)"
# the 3-D view: [K][n][3], x and y those of the bed, z zero, no storage of its own
d=$(dims $f /particles/bed_xyz/position/value)
[ "$d" = "5 $nm 3" ] && paste -d' ' <(h5vals $f $B/position/value | paste -d' ' - -) \
	<(h5vals $f /particles/bed_xyz/position/value | paste -d' ' - - -) | awk '$1 != $3 || $2 != $4 || $5 != 0 { bad = 1 } END { exit bad || NR == 0 }' &&
	h5dump -p -H -d /particles/bed_xyz/position/value $f | grep -q VIRTUAL && ok h5md.xyz_view ||
	fail h5md.xyz_view "/particles/bed_xyz/position/value is [$d] or differs from the bed's positions"
# datasets of 4 KiB or more are chunked, shuffled and deflated (compression = 4 by default),
# smaller ones not: the energy series (1001 doubles) is, the 5 snapshots of 61 disks
# (single precision, 2440 bytes) are not
E=/observables/energy/elastic/value
h5dump -p -H -d $E $f | grep -q "SHUFFLE" && h5dump -p -H -d $E $f | grep -q "DEFLATE" &&
	! h5dump -p -H -d $B/position/value $f | grep -q "DEFLATE" && ok h5md.compressed_when_large ||
	fail h5md.compressed_when_large "$E not shuffled and deflated, or the small $B/position/value is"

# --- XDMF sidecar ---
x=out1.xmf
if [ -s "$x" ]; then
	ok xdmf.exists
	contains $x 'out1.h5:/particles/bed/position/value' && contains $x 'out1.h5:/particles/bed/radius' &&
		contains $x 'out1.h5:/particles/walls/position' && ok xdmf.references_h5 ||
		fail xdmf.references_h5 "$x does not reference out1.h5:/particles/bed/position/value, radius and the walls"
	n=$(grep -c '<Grid Name="t.*CollectionType="Spatial"' $x)
	[ "$n" = 5 ] && ok xdmf.grids || fail xdmf.grids "$n time grids, expected 5"
	contains $x "NumberOfElements=\"$nm\"" && contains $x "NumberOfElements=\"$nw\"" && ok xdmf.elements ||
		fail xdmf.elements "NumberOfElements are not $nm (bed) and $nw (walls)"
else
	fail xdmf.exists "no out1.xmf beside out1.h5"
fi
# no journal or checkpoint left after a successful run
[ ! -e out1.h5.journal ] && [ ! -e my.ckpt ] && ok cleanup || fail cleanup "journal or checkpoint left behind"
finish
