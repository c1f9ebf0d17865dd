#!/bin/sh
# Regenerates the figure gallery docs/figures/gallery/*.png (docs/figures.md): every figure the program draws,
# made by the CLI from the bundled scenarios and data. Takes well under a minute once the binary is
# built (`cargo build --release -p stiction-cli`; the script builds it if needed).
#
#   scripts/gallery.sh            # all figures
#   STICTION=path/to/stiction scripts/gallery.sh
set -eu
cd "$(dirname "$0")/.."
if [ -z "${STICTION:-}" ]; then
    cargo build --release -q -p stiction-cli
    STICTION="${CARGO_TARGET_DIR:-target}/release/stiction"
fi
OUT=docs/figures/gallery
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
mkdir -p "$OUT"
rm -f "$OUT"/*.png
# One size for every figure of the gallery (pixels), so the page reads evenly.
FIG="--width 960 --height 672"
# Runs stiction quietly; on failure shows its error and stops.
s() { "$STICTION" "$@" >/dev/null 2>"$TMP/stderr" || { cat "$TMP/stderr" >&2; exit 1; }; }
take() { cp "$TMP/$1" "$OUT/$2"; }

# The friction meter (Fig. 5 and 7 of the paper), on the paper's device, with its reference values.
s run scenarios/tas2000.json --out "$TMP/run" $FIG
take run/fig5.png run-fig5.png
take run/fig7.png run-fig7.png
# With measured voltages (the bundled synthetic example): measured points and their eq. 10 line.
s run scenarios/tas2000-fit-synthetic.json --out "$TMP/run-measured" $FIG
take run-measured/fig5.png run-measured-fig5.png
take run-measured/fig7.png run-measured-fig7.png

# The paper's figures recomputed.
s plot fig2 --out "$TMP/fig2.png" $FIG
take fig2.png plot-fig2.png
s plot fig3 --out "$TMP/fig3.png" $FIG
take fig3.png plot-fig3.png
s plot fig7 --out "$TMP/fig7.png" $FIG
take fig7.png plot-fig7.png
s plot fig7 --scenario scenarios/tas2000-maugis-dugdale.json --out "$TMP/fig7-md.png" $FIG
take fig7-md.png plot-fig7-maugis-dugdale.png
s plot actuator --scenario scenarios/tas2000.json --out "$TMP/act-clamp.png" $FIG
take act-clamp.png plot-actuator-clamp.png
s plot actuator --scenario scenarios/tas2000.json --array pull --out "$TMP/act-pull.png" $FIG
take act-pull.png plot-actuator-pull.png
# mu_e,a, F_a0 and the capillary share against relative humidity, the measured reference at 35 +/- 5 %.
s plot humidity --scenario scenarios/tas2000-humid.json --out "$TMP/humidity" $FIG
take humidity/humidity-mu.png plot-humidity-mu.png
take humidity/humidity-fa0.png plot-humidity-fa0.png
take humidity/humidity-share.png plot-humidity-share.png

# Monte Carlo study.
s study scenarios/tas2000.json --samples 300 --quiet --out "$TMP/study" $FIG
take study/mu_cdf.png study-mu-cdf.png
take study/mu_vs_fa0.png study-mu-vs-fa0.png
take study/sensitivity_indices.png study-sensitivity.png

# Fits of measured voltages.
s fit --scenario scenarios/tas2000-fit-synthetic.json --surfaces 20 --draws 1000 --out "$TMP/fit" $FIG
take fit/fit-vpull2.png fit-vpull2.png
take fit/fit-friction-load.png fit-friction-load.png
take fit/fit-residuals.png fit-residuals.png

# Test structures built from parts: the comb tester's Fig. 5 and 7, the plate's Fig. 7 (release
# protocol: no pull voltage, so no Fig. 5) and a fit of (synthetic) release thresholds.
s run scenarios/comb-sidewall.json --out "$TMP/comb" $FIG
take comb/fig5.png structure-comb-fig5.png
take comb/fig7.png structure-comb-fig7.png
s run scenarios/plate-released-spring.json --out "$TMP/plate" $FIG
take plate/fig7.png structure-plate-fig7.png
s fit data/structure-thresholds-synthetic/release.csv --scenario scenarios/plate-released-spring.json \
    --out "$TMP/fit-structure" $FIG
take fit-structure/fit-friction-load.png structure-fit-friction-load.png

# Gap-closing actuators against measured hardware.
s actuator scenarios/gca-rauf2022.json --validate data/gca-pullin-release/measured.csv --out "$TMP/gca" $FIG
take gca/validation.png actuator-validation.png
take gca/hysteresis.png actuator-hysteresis.png
s actuator scenarios/gca-rauf2022.json --transients data/gca-transients/measured_times.csv --out "$TMP/tr" $FIG
take tr/transients_L38.25um.png actuator-transients-L38um.png

# A height map.
s topography data/topography-example/wall.gsf --out "$TMP/topo" $FIG
for f in height_map psd summit_heights summit_radii; do take "topo/$f.png" "topography-$f.png"; done

# Boundary-element contact.
s bem --map data/topography-example/wall.gsf --e-star "82.4 GPa" --sweep 2MPa:2GPa:8 --compare-asperity --out "$TMP/bem" $FIG
for f in "$TMP"/bem/*.png; do n=$(basename "$f"); cp "$f" "$OUT/bem-$n"; done

ls "$OUT" | wc -l | xargs echo "gallery: PNG files in $OUT:"
