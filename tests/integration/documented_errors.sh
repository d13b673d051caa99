#!/usr/bin/env bash
# documented_errors.sh - errors the docs promise, each with its exit code and its words:
# settling that does not converge (exit 6, docs/scene.md), a particle file over 8 GiB, a
# LAMMPS box line with words after it (docs/inputs.md), inf/nan/subnormal numbers on the
# command line, an HDF5 file of another program and a text file where a run file
# belongs, a campaign file that is a directory or a device.
. "$(dirname "$0")/lib.sh"
STUDY="${STUDY:-$(dirname "$SHAKE")/study}"
cd "$TMP" || exit 1

# expect ID CODE PATTERN command... : exit CODE and PATTERN (extended regex) in its output
expect() {
	local id=$1 code=$2 pat=$3 rc
	shift 3
	"$@" >"$id.log" 2>&1
	rc=$?
	if [ "$rc" = "$code" ] && { [ -z "$pat" ] || grep -Eq "$pat" "$id.log"; }; then
		ok "$id"
	else
		fail "$id" "exit $rc (want $code), output: $(head -c 300 "$id.log")"
	fi
}

# --- exit 6: settling did not converge; the file is still written, with the reason ---
expect settle.not_converged 6 "settling: mean kinetic energy .* still above settle_ke = 1e-09 after settle_max = 0.3 s" \
	"$SHAKE" "${FAST[@]}" settle_ke=1e-9 settle_max=0.3 output=s6.h5
[ "$(attr s6.h5 /exit_code)" = 6 ] && attr s6.h5 /status_message | grep -q "settle_max" &&
	ok settle.not_converged.file_with_message ||
	fail settle.not_converged.file_with_message "exit_code '$(attr s6.h5 /exit_code)', message '$(attr s6.h5 /status_message)'"

# --- a particle file over 8 GiB: refused before a byte is read (a sparse file) ---
truncate -s 9G big.txt
expect particles.over_8GiB 1 "big.txt: 9663676416 bytes, more than the 8589934592 a particle file may have" \
	"$SHAKE" particles=big.txt duration=0 progress=no output=big.h5
rm -f big.txt
[ ! -e big.h5 ] && ok particles.over_8GiB.no_output || fail particles.over_8GiB.no_output "big.h5 written"

# --- a LAMMPS box line is read whole: words after xhi are refused, not skipped ---
"$SHAKE" "${FAST[@]}" duration=0 write_lammps=plain.data output=none >w.log 2>&1 || fail lammps.setup "$(cat w.log)"
expect lammps.box_line_plain 0 "" "$SHAKE" particles=plain.data settle=no duration=0 progress=no output=plain.h5
line=$(grep -n ' xlo xhi$' plain.data | cut -d: -f1)
sed 's/ xlo xhi$/ xlo xhi extra words/' plain.data >trail.data
expect lammps.box_line_trailing_words 1 "trail.data:$line: expected 'lo hi xlo xhi', got words after xhi" \
	"$SHAKE" particles=trail.data settle=no duration=0 progress=no output=trail.h5

# --- numbers that are no numbers of the range, on the command line ---
for v in inf -inf nan Infinity 1e-320 0x10; do
	expect "cmdline.frequency.$v" 1 "command line: frequency: expected a number in \[0, 1000\], got '$v'" \
		"$SHAKE" "${FAST[@]}" frequency="$v" duration=0 output=n.h5
done
expect cmdline.dt.subnormal 1 "command line: dt: " "$SHAKE" "${FAST[@]}" dt=4.9e-324 duration=0 output=n.h5

# --- a file that is no run file of this engine, where a run file belongs ---
DUMPFLUX="$(dirname "$SHAKE")/dumpflux"
/usr/bin/python3 -c 'import h5py, sys; f = h5py.File(sys.argv[1], "w"); f["x"] = [1, 2, 3]; f.close()' foreign.h5
expect runfile.foreign_hdf5 2 "foreign.h5: not a shakebox run file \(no format attribute\)" "$DUMPFLUX" run foreign.h5
echo "hello" >text.h5
expect runfile.not_hdf5 2 "text.h5: not a shakebox run file \(no HDF5 signature at byte 0 or 512\)" "$DUMPFLUX" run text.h5

# a string attribute longer than 1 MiB (docs/inputs.md) is not read: a run file whose
# format attribute is 2 MiB, sealed again (build/fuzz/h5mut), is no run file; the same
# file resealed without the change is read
H5MUT="$REPO/build/fuzz/h5mut"
"$SHAKE" "${FAST[@]}" "${GENTLE[@]}" flux=yes duration=0.5 output=r.h5 >r.log 2>&1 || fail runfile.setup "$(tail -n 2 r.log)"
"$H5MUT" r.h5 ctl.h5 --attr-str / description resealed >h5m.log 2>&1 || fail runfile.setup "$(cat h5m.log)"
expect runfile.resealed_control 0 "" "$DUMPFLUX" run ctl.h5
cp r.h5 long.h5
/usr/bin/python3 -c 'import h5py, numpy, sys
f = h5py.File(sys.argv[1], "a"); del f.attrs["format"]; f.attrs.create("format", numpy.bytes_(b"x" * (2 << 20))); f.close()' long.h5
"$H5MUT" long.h5 long2.h5 --attr-str / description resealed >h5m.log 2>&1 || fail runfile.setup "$(cat h5m.log)"
expect runfile.string_over_1MiB 2 "long2.h5: not a shakebox run file \(its format attribute is not one string of at most 1 MiB\)" \
	"$DUMPFLUX" run long2.h5

# --- a campaign file that is a directory or a device ---
mkdir cdir
expect campaign.directory 1 "cdir: is a directory, not a regular file: a campaign file must be a regular file" \
	"$STUDY" run cdir --runs R
expect campaign.char_device 1 "/dev/null: is a character device, not a regular file" "$STUDY" run /dev/null --runs R
[ ! -e R ] && ok campaign.refused.nothing_made || fail campaign.refused.nothing_made "$(ls -R R | head -n 5)"
finish
