#!/usr/bin/env bash
# The accuracy-versus-time studies shipped in docs/study.md and the README: each line below runs
# one `kasumi study` and writes docs/studies/<name>/study.{csv,md,svg}. Resolutions are small so
# the whole script finishes in minutes on two shared cores.
#
# usage: bench/studies.sh [NAME...]     (no names: every study)
#   KASUMI=path/to/kasumi  (default build/release/apps/kasumi)
#   OUT=dir                (default docs/studies)
#   THREADS=n              (default 2)
# To add a study, add one `study NAME SCENE ARGS...` line (any `kasumi study` arguments).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
kasumi="$(realpath "${KASUMI:-$root/build/release/apps/kasumi}")"
out="${OUT:-$root/docs/studies}"
threads="${THREADS:-2}"
selected=("$@")
cd "$root"  # scene paths in the reports stay relative to the repository

study() {  # NAME SCENE ARGS...
  local name="$1" scene="$2"
  shift 2
  if [ "${#selected[@]}" -gt 0 ] && [[ ! " ${selected[*]} " =~ " $name " ]]; then
    return 0
  fi
  echo "== $name: kasumi study $scene $*" >&2
  local start=$SECONDS
  "$kasumi" study "$scene" --threads "$threads" -q "$@" -o "$out/$name"
  echo "   $name done in $((SECONDS - start)) s" >&2
}

# Fog: march step of the homogeneous fog x samples per pixel.
study fog data/scenes/fog_street.json --res 96x54 --repeats 3 \
  --vary /render/volume/step_m=1.6,0.8,0.4,0.2 --vary spp=1,4,16 --reference-spp 256

# Height fog (data/scenes/fog_height.json), single scattering: the march of a lone height fog
# (nodes stratified in the closed-form column, unbiased) step x spp, against the march at 1 m
# and 256 spp; then the march at 4 m against the trackers (one free-flight point per path); then
# multiple scattering, transmittance estimator x spp (march: the closed form), against residual
# ratio tracking at 1024 spp.
study fog-height data/scenes/fog_height.json --res 96x54 --repeats 3 \
  --set /render/volume/estimator=march --vary /render/volume/step_m=16,4,1,0.25 \
  --vary spp=1,4,16 --reference-set /render/volume/step_m=1 --reference-spp 256
study fog-height-estimator data/scenes/fog_height.json --res 96x54 --repeats 3 \
  --set /render/volume/step_m=4 --vary /render/volume/estimator=march,delta,ratio,residual-ratio \
  --vary spp=1,4,16 --reference-set /render/volume/estimator=march \
  --reference-set /render/volume/step_m=1 --reference-spp 256
study fog-height-multiple data/scenes/fog_height.json --res 96x54 --repeats 3 \
  --set /render/volume/integrator=multiple \
  --vary /render/volume/estimator=march,delta,ratio,residual-ratio --vary spp=1,4,16 \
  --reference-set /render/volume/estimator=residual-ratio --reference-spp 1024

# Cloud, multiple scattering: transmittance estimator x spp.
study cloud-estimator data/scenes/cloud.json --res 96x54 --repeats 3 \
  --vary /render/volume/estimator=march,delta,ratio,residual-ratio --vary spp=1,4,16 \
  --reference-spp 512

# Cloud, single scattering by the classic ray march: step (voxels) x spp, against an unbiased
# single-scattering reference (ratio tracking).
study cloud-step data/scenes/cloud.json --res 96x54 --repeats 3 \
  --set /render/volume/integrator=single --set /render/volume/estimator=march \
  --vary /render/volume/step_voxels=4,2,1,0.5 --vary spp=1,4,16 \
  --reference-set /render/volume/estimator=ratio --reference-spp 512

# Cloud: single against multiple scattering x spp (the reference is multiple scattering).
study cloud-scattering data/scenes/cloud.json --res 96x54 --repeats 3 \
  --vary /render/volume/integrator=single,multiple --vary spp=1,4,16 --reference-spp 512

# Clouds, multiple scattering: the shadow-ray roulette x the camera segment's transmittance x
# adaptive sampling x 4 seeds, against today's settings (what render.quality's levels choose:
# scene/quality.cpp). Shipped from THREADS=1 runs; docs/studies/cloud-ms-sampling/
# instructions.txt has the cost in instructions (callgrind) that the choice used. The 256³
# cumulus is made here; the WDAS cloud needs ../shared/data.
ms_sampling=(--vary spp=16,64 --vary /render/volume/shadow_roulette=0,0.05
  --vary /render/volume/camera_transmittance=walk,first_flight --vary /film/noise_threshold=0,0.1
  --vary /render/seed=1,2,3,4 --set '/render/volume/estimator="ratio"'
  --reference-set /render/seed=999 --reference-set /render/volume/shadow_roulette=0
  --reference-set '/render/volume/camera_transmittance="walk"' --reference-set /film/noise_threshold=0
  --repeats 3)
study cloud-ms-sampling data/scenes/cloud.json --res 96x54 --reference-spp 4096 "${ms_sampling[@]}"
cumulus_256="${TMPDIR:-/tmp}/kasumi_cumulus_256.vdb"
if [ "${#selected[@]}" -eq 0 ] || [[ " ${selected[*]} " =~ " cloud-ms-sampling-cumulus " ]] ||
  [[ " ${selected[*]} " =~ " cloud-denoise-cumulus " ]] ||
  [[ " ${selected[*]} " =~ " cloud-denoise-select-cumulus " ]]; then
  "$kasumi" make-cloud --res 256 --seed 7 -o "$cumulus_256" >/dev/null
fi
study cloud-ms-sampling-cumulus data/scenes/cloud.json --res 96x54 --reference-spp 1024 \
  --set "/media/0/file=\"$cumulus_256\"" "${ms_sampling[@]}"
if [ -f ../shared/data/wdas_cloud_sixteenth.vdb ]; then
  study cloud-ms-sampling-wdas data/scenes/cloud_wdas.json --res 64x64 --reference-spp 1024 \
    "${ms_sampling[@]}"
fi

# Clouds, multiple scattering: the denoiser x the two unbiased settings above x seeds, against
# today's raw settings (docs/denoising.md; the cost the docs quote is callgrind's, in
# docs/studies/cloud-denoise/instructions.txt).
denoise_grid=(--vary /film/denoise=off,nlm --vary /render/volume/shadow_roulette=0,0.05
  --vary /render/volume/camera_transmittance=walk,first_flight
  --reference-set /render/seed=999 --reference-set /film/denoise=off
  --reference-set /render/volume/shadow_roulette=0
  --reference-set '/render/volume/camera_transmittance="walk"')
study cloud-denoise data/scenes/cloud.json --res 96x54 --reference-spp 4096 --repeats 3 \
  --vary spp=16,64 --vary /render/seed=1,2,3,4,5,6 "${denoise_grid[@]}"
study cloud-denoise-cumulus data/scenes/cloud.json --res 96x54 --reference-spp 1024 --repeats 2 \
  --set "/media/0/file=\"$cumulus_256\"" --vary spp=16 --vary /render/seed=1,2,3,4 "${denoise_grid[@]}"
if [ -f ../shared/data/wdas_cloud_sixteenth.vdb ]; then
  study cloud-denoise-wdas data/scenes/cloud_wdas.json --res 64x64 --reference-spp 1024 --repeats 2 \
    --vary spp=16 --vary /render/seed=1,2,3,4 "${denoise_grid[@]}"
fi
# The denoiser's strength selected per pixel by a SURE estimate of its error (film.denoise
# "select", docs/denoising.md) beside the plain filter: the same grid and reference.
study cloud-denoise-select data/scenes/cloud.json --res 96x54 --reference-spp 4096 --repeats 1 \
  --vary spp=16,64 --vary /render/seed=1,2,3,4,5,6 --vary '/film/denoise=off,nlm,{"select":true}' \
  --vary /render/volume/shadow_roulette=0,0.05 --vary /render/volume/camera_transmittance=walk,first_flight \
  --reference-set /render/seed=999 --reference-set /film/denoise=off \
  --reference-set /render/volume/shadow_roulette=0 --reference-set '/render/volume/camera_transmittance="walk"'
select_grid=(--vary spp=64 --vary /render/seed=1,2,3,4 --vary '/film/denoise=off,nlm,{"select":true}'
  --vary /render/volume/shadow_roulette=0,0.05 --vary /render/volume/camera_transmittance=walk,first_flight
  --reference-set /render/seed=999 --reference-set /film/denoise=off
  --reference-set /render/volume/shadow_roulette=0
  --reference-set '/render/volume/camera_transmittance="walk"' --repeats 1)
study cloud-denoise-select-cumulus data/scenes/cloud.json --res 96x54 --reference-spp 1024 \
  --set "/media/0/file=\"$cumulus_256\"" "${select_grid[@]}"
if [ -f ../shared/data/wdas_cloud_sixteenth.vdb ]; then
  study cloud-denoise-select-wdas data/scenes/cloud_wdas.json --res 64x64 --reference-spp 1024 \
    "${select_grid[@]}"
fi

# Transmittance probes, estimator x samples: exact errors where a closed form exists. The
# homogeneous fog against Beer-Lambert exp(-tau) (the march integrates tau analytically there,
# so only the trackers are studied); the cloud's edge (T ~ 0.17) against ratio tracking at 1e6.
study fog-transmittance data/scenes/fog_street.json --repeats 5 \
  --probe transmittance --from 0,1,0 --to 0,1,30 --exact beer-lambert \
  --vary /render/volume/estimator=delta,ratio,residual-ratio --vary spp=100,1000,10000
study cloud-transmittance data/scenes/cloud.json --repeats 5 \
  --probe transmittance --from -800,560,0 --to 800,560,0 --reference-spp 1000000 \
  --vary /render/volume/estimator=march,delta,ratio,residual-ratio --vary spp=100,1000,10000

# Sky: fast tables against the reference ray march x RGB or N wavelengths, against the
# reference march at 32 wavelengths. Times are render_image only: the fast mode's tables are
# built when the scene loads (bench/sky_bench.sh times them).
study sky data/scenes/sky.json --res 48x27 --repeats 3 \
  --vary /render/sky/mode=fast,reference --vary /render/spectral=rgb,8,16 \
  --reference-set /render/spectral=32 --reference-spp 16

# Soft shadows: shadow samples of both area lights x spp.
study soft-shadows data/scenes/soft_shadows.json --res 96x54 --repeats 3 \
  --vary /lights/0/samples+/lights/1/samples=1,4,16 --vary spp=1,4,16 --reference-spp 256

# Shadows: shadow maps of 256..1024 texels (every light at once: the sun's orthographic map,
# the spot's perspective map, the bulb's cube map) against ray-traced shadows x spp; the
# reference is ray-traced at 256 spp (the automatic reference takes the last value listed for
# objects, so "ray" comes last). Timed with the build (--time build+render): a map is rendered
# from its light for every image, and that is its cost. 2048 and 4096 are left out for time (the
# bulb's cube alone is 25 M and 100 M depth rays; docs/lights.md has 2048 from shadow_study.sh).
map() { echo "{\"shadows\":\"map\",\"shadow_map\":{\"resolution\":$1}}"; }
study shadows data/scenes/shadow_maps.json --res 160x100 --repeats 3 --time build+render \
  --vary "/lights/*=$(map 256),$(map 512),$(map 1024),{\"shadows\":\"ray\"}" \
  --vary spp=1,4,16 --reference-spp 256

# Area-light shadows: shadow maps from 8 view points per light (128 and 256 texels) against
# ray-traced shadows x area-light samples, on soft_shadows.json without its haze (maps replace
# the shadow rays of surfaces only; the fog's march would dominate the time and hide them), at
# 4 spp, against ray-traced shadows with 16 samples per light at 256 spp.
study area-shadows data/scenes/soft_shadows.json --res 160x90 --repeats 3 --time build+render \
  --set '/media=[]' --spp 4 \
  --vary "/lights/*=$(map 128),$(map 256),{\"shadows\":\"ray\"}" \
  --vary '/lights/*/samples=1,4,16' --reference-spp 256

# Area-light samples x spp with ray-traced shadows on the same haze-free soft_shadows.json: is a
# second sample better spent on the light or on the pixel? Reference as above.
study area-samples data/scenes/soft_shadows.json --res 160x90 --repeats 3 --set '/media=[]' \
  --vary '/lights/*/samples=1,4,16' --vary spp=1,4,16 --reference-spp 256

# Global illumination on the Cornell box: radiosity vs photon mapping vs the path tracer x spp,
# against the path tracer at 4096 spp. Times are render_image only: the radiosity solve and the
# photon maps are built when the scene loads (docs/gi.md gives them). The box has no mirror or
# glass, so the caustic pass is turned off.
study gi data/scenes/cornell_box.json --res 32x32 --repeats 3 \
  --vary /render/gi=radiosity,photons,path --vary spp=1,4,16 \
  --set '/render/photons={"caustic_count":0}' \
  --reference-set '/render/gi="path"' --reference-spp 4096

# Clouds, multiple scattering: adaptive sampling, film.noise_threshold 0 / 0.1 / 0.2 x
# film.noise_window 0 (the pixel's own rule) / 1 / 2 (the neighbourhood pilot rule) x seeds 1-4
# at 64 spp, with the quality levels' cloud sampling, against uniform renders of another seed
# (docs/volumes.md "Adaptive sampling"; scene/quality.cpp). Shipped from THREADS=1 runs; the
# cost the docs quote is callgrind's, docs/studies/cloud-ms-adaptive/instructions.txt.
adaptive=(--spp 64 --vary /film/noise_threshold=0,0.1,0.2 --vary /film/noise_window=0,1,2
  --vary /render/seed=1,2,3,4 --set /render/volume/shadow_roulette=0.05
  --set '/render/volume/camera_transmittance="first_flight"' --set '/render/volume/estimator="ratio"'
  --reference-set /film/noise_threshold=0 --reference-set /render/seed=999 --repeats 1)
study cloud-ms-adaptive data/scenes/cloud.json --res 96x54 --reference-spp 2048 "${adaptive[@]}"
[ -f "$cumulus_256" ] || "$kasumi" make-cloud --res 256 --seed 7 -o "$cumulus_256" >/dev/null
study cloud-ms-adaptive-cumulus data/scenes/cloud.json --res 96x54 --reference-spp 1024 \
  --set "/media/0/file=\"$cumulus_256\"" "${adaptive[@]}"
if [ -f ../shared/data/wdas_cloud_sixteenth.vdb ]; then
  study cloud-ms-adaptive-wdas data/scenes/cloud_wdas.json --res 96x54 --reference-spp 2048 \
    "${adaptive[@]}"
fi
