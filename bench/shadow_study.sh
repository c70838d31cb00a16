#!/usr/bin/env bash
# Shadow maps against ray-traced shadows (docs/lights.md, "Measured"): renders each scene with
# ray-traced shadows and with shadow maps of resolution 256..4096 (area lights: up to
# MAX_AREA_RES, their maps being views x 6 faces), and with shadow volumes where the scene has
# them; prints a Markdown table of the fraction of pixels whose luminance differs by more than
# 1%, the RMSE (cd/m²) against the ray-traced render, and the median wall time of RUNS renders
# (map building included). The same seed gives both renders the same samples, so the
# difference is the visibility alone. The accuracy-per-second view of the same question (error
# against a converged ray-traced reference, map builds timed, Pareto front) is the `kasumi
# study` run `bench/studies.sh shadows area-shadows area-samples` (docs/study.md).
#
# The polygon block (SCENES "polygons") puts the lecture's umbra methods side by side on the
# polygon scenes shadow_volumes.json and shadow_polygons_concave.json, with their point light
# and with a directional light: ray tracing, object-space detail polygons, shadow volumes and a
# 2048² shadow map, each at three image sizes, with the
# shadow stage's build time (from `render -v`: build/object-space, build/shadow-volumes,
# build/shadow-maps) and the render time per pixel, and the error against ray tracing at the
# same size. The scanline method ("shadows": "scanline", build/scanline: the pass) answers camera
# hits at pixel centres only, so its row renders with film.jitter false and is compared with a
# ray-traced render without jitter (rendered for it, not timed in the table). The row
# "scanline-surface" is the scanline renderer as a whole (render.surface "scanline" and
# "shadows": "scanline": visible surfaces and shadows from the scanline pass, no camera or shadow
# ray for them; build/scanline then holds both passes), compared the same way.
#
# Usage: bench/shadow_study.sh [BUILD_DIR]   (default build/release; needs targets kasumi and
#        shadow_compare).  Environment: RUNS (default 3), THREADS (default 2), OUT (scratch dir),
#        RESOLUTIONS (default "256 512 1024 2048 4096"), MAX_AREA_RES (default 1024),
#        SCENES (default "shadow_maps soft_shadows shadow_volumes polygons"), EXTRA (more render
#        arguments, e.g. "--res 320x200 --spp 1" on a busy machine), POLYGON_SIZES (default
#        "320x200 640x400 1280x800"), POLYGON_METHODS (default "ray scanline scanline-surface
#        object-space shadow-volume map").
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build/release}
KASUMI=$BUILD/apps/kasumi
COMPARE=$BUILD/bench/shadow_compare
RUNS=${RUNS:-3}
THREADS=${THREADS:-2}
OUT=${OUT:-$(mktemp -d /tmp/kasumi_shadow_study.XXXXXX)}
RESOLUTIONS=${RESOLUTIONS:-"256 512 1024 2048 4096"}
MAX_AREA_RES=${MAX_AREA_RES:-1024}
SCENES=${SCENES:-"shadow_maps soft_shadows shadow_volumes polygons"}
POLYGON_SIZES=${POLYGON_SIZES:-"320x200 640x400 1280x800"}
POLYGON_METHODS=${POLYGON_METHODS:-"ray scanline scanline-surface object-space shadow-volume map"}
read -r -a EXTRA_ARGS <<< "${EXTRA:-}"
mkdir -p "$OUT"

# render NAME SCENE ARGS...: RUNS renders to $OUT/NAME.exr; prints the median wall time (s).
render() {
    local name=$1 scene=$2
    shift 2
    local times=()
    for ((run = 0; run < RUNS; ++run)); do
        local start end
        start=$(date +%s.%N)
        "$KASUMI" render "$scene" -o "$OUT/$name.exr" --threads "$THREADS" -q "${EXTRA_ARGS[@]}" "$@"
        end=$(date +%s.%N)
        times+=("$(echo "$end - $start" | bc -l)")
    done
    printf '%s\n' "${times[@]}" | sort -g | awk '{t[NR] = $1} END {printf "%.2f", t[int((NR + 1) / 2)]}'
}

# compare REF TEST: "differ_fraction | rmse"
compare() {
    "$COMPARE" "$OUT/$1.exr" "$OUT/$2.exr" 0.01 |
        sed -E 's/.*"differ_fraction": ([^,]*), "rmse": ([^,]*),.*/\1 | \2/'
}

# study NAME SCENE LIGHT_COUNT MAX_RES: one table block for a scene whose first LIGHT_COUNT
# lights are switched between "ray" and "map".
study() {
    local name=$1 scene=$2 count=$3 max_res=$4
    local ray_sets=() i
    for ((i = 0; i < count; ++i)); do ray_sets+=(--set "/lights/$i/shadows=ray"); done
    local t_ray
    t_ray=$(render "${name}_ray" "$scene" "${ray_sets[@]}")
    echo "| $name | ray-traced | 0 | 0 | $t_ray |"
    for res in $RESOLUTIONS; do
        ((res > max_res)) && continue
        local map_sets=()
        for ((i = 0; i < count; ++i)); do
            map_sets+=(--set "/lights/$i/shadows=map" --set "/lights/$i/shadow_map={\"resolution\": $res}")
        done
        local t
        t=$(render "${name}_map$res" "$scene" "${map_sets[@]}")
        echo "| $name | map $res² | $(compare "${name}_ray" "${name}_map$res") | $t |"
    done
}

# timed NAME SCENE ARGS...: RUNS verbose renders to $OUT/NAME.exr; prints "build_ms ns_per_pixel"
# (medians): the shadow stage's build time and the render time divided by the pixel count.
timed() {
    local name=$1 scene=$2
    shift 2
    local builds=() per_pixel=()
    for ((run = 0; run < RUNS; ++run)); do
        local stats
        stats=$("$KASUMI" render "$scene" -o "$OUT/$name.exr" --no-preview --threads "$THREADS" -v \
            "${EXTRA_ARGS[@]}" "$@" 2>&1)
        builds+=("$(awk '$1 == "time" && $2 ~ /^build\/(shadow-maps|shadow-volumes|object-space|scanline)$/ \
            {s += $3} END {printf "%.2f", 1000 * s}' <<< "$stats")")
        per_pixel+=("$(awk '$1 == "time" && $2 == "render" {t = $3}
            $1 == "camera" && $2 == "rays" {n = $3} END {printf "%.0f", 1e9 * t / n}' <<< "$stats")")
    done
    local median='sort -g | awk "{t[NR] = \$1} END {print t[int((NR + 1) / 2)]}"'
    echo "$(printf '%s\n' "${builds[@]}" | eval "$median") $(printf '%s\n' "${per_pixel[@]}" | eval "$median")"
}

# polygons: the umbra methods on the polygon scenes, point and directional light, three sizes.
polygons() {
    local sun='{"name": "sun", "type": "directional", "direction": [0.4, -1, -0.3], "illuminance_lux": 3}'
    echo
    echo "| scene | light | shadows | size | build (ms) | render (ns/pixel) | pixels differing (> 1%) | RMSE (cd/m²) |"
    echo "|---|---|---|---|---|---|---|---|"
    local scene light size method
    for scene in shadow_volumes shadow_polygons_concave; do
        for light in point directional; do
            local light_sets=()
            [[ $light == directional ]] && light_sets=(--set "/lights/0=$sun")
            for size in $POLYGON_SIZES; do
                for method in $POLYGON_METHODS; do
                    local shadows=$method
                    [[ $method == scanline-surface ]] && shadows=scanline
                    local sets=(--res "$size" "${light_sets[@]}" --set "/lights/0/shadows=\"$shadows\"")
                    [[ $method == scanline-surface ]] && sets+=(--set '/render/surface="scanline"')
                    [[ $method == map ]] && sets+=(--set '/lights/0/shadow_map={"resolution": 2048}')
                    local name="poly_${scene}_${light}_${size}_${method}" build per_pixel error
                    local reference="poly_${scene}_${light}_${size}_ray"
                    if [[ $method == scanline || $method == scanline-surface ]]; then
                        # The pass answers camera hits at pixel centres only: both renders
                        # without jitter, the scanline one against a ray-traced one like it.
                        sets+=(--set /film/jitter=false)
                        reference="${name}_ray_centres"
                        timed "$reference" "data/scenes/$scene.json" --res "$size" \
                            "${light_sets[@]}" --set '/lights/0/shadows="ray"' \
                            --set /film/jitter=false > /dev/null
                    fi
                    read -r build per_pixel <<< "$(timed "$name" "data/scenes/$scene.json" "${sets[@]}")"
                    if [[ $method == ray ]]; then
                        error="0 | 0"
                    else
                        error=$(compare "$reference" "$name")
                    fi
                    echo "| $scene | $light | $method | $size | $build | $per_pixel | $error |"
                done
            done
        done
    done
}

echo "| scene | shadows | pixels differing (> 1%) | RMSE (cd/m²) | time (s, median of $RUNS) |"
echo "|---|---|---|---|---|"
for scene in $SCENES; do
    case $scene in
    shadow_maps) study shadow_maps data/scenes/shadow_maps.json 3 4096 ;;
    soft_shadows) study soft_shadows data/scenes/soft_shadows.json 2 "$MAX_AREA_RES" ;;
    shadow_volumes)
        t_ray=$(render volumes_ray data/scenes/shadow_volumes.json --set /lights/0/shadows=ray)
        echo "| shadow_volumes | ray-traced | 0 | 0 | $t_ray |"
        t_vol=$(render volumes_sv data/scenes/shadow_volumes.json)
        echo "| shadow_volumes | shadow-volume | $(compare volumes_ray volumes_sv) | $t_vol |"
        ;;
    polygons) polygons ;;
    esac
done
