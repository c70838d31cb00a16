#!/usr/bin/env bash
# Sky data from files: an atmosphere coefficient and the sun's spectrum given as CSV tables next
# to the scene render from any working directory; a bad table is an input error (exit 3) that
# names the scene file, the JSON pointer, the CSV file and line; a table that does not cover the
# render's wavelengths is an input error too; nothing is written on error.
# usage: sky_data_cli_test.sh KASUMI_BINARY SOURCE_DIR
set -u
kasumi="$1"
src="$2"
source "$(dirname "$0")/cli_lib.sh"

mkdir -p "$work/scene/tables" "$work/elsewhere"
cat >"$work/scene/sky.json" <<'JSON'
{
  "camera": {"position": [0, 1.5, 0], "look_at": [0, 2.5, -1], "fov_deg": 90},
  "film": {"width": 16, "height": 9, "spp": 1},
  "atmosphere": {"rayleigh": {"scattering": "tables/rayleigh.csv"},
                 "ozone": {"absorption": "auto", "column_du": 320}},
  "sun": {"elevation_deg": 20, "azimuth_deg": 180, "spectrum": "tables/sun.csv"},
  "render": {"sky": {"mode": "reference", "orders": 1, "view_steps": 16, "sun_steps": 8},
             "spectral": 8}
}
JSON
# Rayleigh scattering of standard air at a few wavelengths (Bucholtz 1995 magnitudes), 1/m.
cat >"$work/scene/tables/rayleigh.csv" <<'CSV'
# wavelength_nm, sigma_s (1/m)
wavelength_nm,value
360,6.0e-5
450,2.4e-5
550,1.15e-5
700,4.2e-6
830,2.1e-6
CSV
printf '360,1\n830,1\n' >"$work/scene/tables/sun.csv"

# Renders from another working directory: tables are found next to the scene file.
(cd "$work/elsewhere" && expect_exit 0 "" -- render ../scene/sky.json -o "$work/out/good.exr" -q)
[ -s "$work/out/good.exr" ] || fail "no image from the scene with CSV tables"
(cd "$work/elsewhere" && expect_exit 0 "" -- check "$work/scene/sky.json")

# A bad row: exit 3, one line naming scene file, pointer, CSV file and line.
printf '# header comment\n360,1e-5\n450,oops\n830,1e-6\n' >"$work/scene/tables/rayleigh.csv"
expect_exit 3 "sky.json: /atmosphere/rayleigh/scattering.*rayleigh.csv:3: expected two numbers" -- \
  render "$work/scene/sky.json" -o "$work/out/bad.exr" -q
[ "$(wc -l <"$work/stderr")" -eq 1 ] || fail "error message is not one line: $(cat "$work/stderr")"
[ -e "$work/out/bad.exr" ] && fail "an input error wrote output"

# Wavelengths out of order.
printf '360,1e-5\n600,1e-5\n500,1e-6\n830,1e-6\n' >"$work/scene/tables/rayleigh.csv"
expect_exit 3 "rayleigh.csv:3: wavelengths must strictly increase" -- check "$work/scene/sky.json"

# A table that does not cover the spectral wavelengths (8 bins: 389.4 to 800.6 nm).
printf '400,1e-5\n830,1e-6\n' >"$work/scene/tables/rayleigh.csv"
expect_exit 3 "/atmosphere/rayleigh/scattering.*no value at 389.* the table covers 400 to 830 nm" -- \
  render "$work/scene/sky.json" -o "$work/out/range.exr" -q
[ -e "$work/out/range.exr" ] && fail "an input error wrote output"

# A missing sun table.
printf '360,1e-5\n830,1e-6\n' >"$work/scene/tables/rayleigh.csv"
rm "$work/scene/tables/sun.csv"
expect_exit 3 "/sun/spectrum.*sun.csv: cannot open" -- check "$work/scene/sky.json"

finish "sky data cli"
