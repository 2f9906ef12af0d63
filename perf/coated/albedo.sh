#!/usr/bin/env bash
# Directional albedo of coateddiffuse, Lantern against pbrt-v4: a large
# plane under a uniform white sky, seen through a 1-degree camera at view
# angle THETA from its normal, maxdepth 1, so the image's mean is the
# material's directional albedo at THETA (times the sky's radiance, 1).
#   perf/coated/albedo.sh LANTERN [PBRT] [OUT_DIR]
#   MATERIAL=coatedconductor perf/coated/albedo.sh ...   (gold, or a metal by
#     reflectance, under coats of the same roughnesses)
# Prints one line per (roughness, reflectance, theta): Lantern's mean RGB,
# pbrt-v4's, and their ratio. Without PBRT only Lantern's column is filled.
set -euo pipefail
LANTERN=$1; PBRT=${2:-}; OUT=${3:-/tmp/coated-albedo}
SPP=${SPP:-1024}
MATERIAL=${MATERIAL:-coateddiffuse}
mkdir -p "$OUT"
mean() { "$LANTERN" compare "$1" "$1" | awk '/^mean /{printf "%.4f %.4f %.4f", $2, $3, $4}'; }
printf "%-5s %-13s %-5s | %-22s | %-22s | %s\n" rough reflectance theta lantern pbrt-v4 ratio
for rough in 0 0.1 0.3; do
  for refl in "0.8 0.4 0.1" "0.5 0.5 0.5"; do
    for theta in 0 45 75; do
      name="r${rough}_$(echo "$refl" | tr ' ' '-')_t${theta}"
      read -r cx cz < <(awk -v t="$theta" 'BEGIN{r=t*3.14159265358979/180; printf "%.6f %.6f\n", 5*sin(r), 5*cos(r)}')
      up="0 0 1"; [ "$theta" = 0 ] && up="0 1 0"
      if [ "$MATERIAL" = coatedconductor ]; then
        # The "reflectance" column: a grey metal by reflectance, or gold (its eta and k).
        if [ "$refl" = "0.5 0.5 0.5" ]; then base='"rgb reflectance" [ 0.5 0.5 0.5 ]'
        else base='"spectrum conductor.eta" "metal-Au-eta" "spectrum conductor.k" "metal-Au-k"'; fi
        material="Material \"coatedconductor\" \"float interface.roughness\" [ $rough ] \"float conductor.roughness\" [ 0.2 ] $base"
      else
        material="Material \"coateddiffuse\" \"rgb reflectance\" [ $refl ] \"float roughness\" [ $rough ]"
      fi
      cat > "$OUT/$name.pbrt" <<SCENE
LookAt $cx 0 $cz  0 0 0  $up
Camera "perspective" "float fov" [ 1 ]
Sampler "independent" "integer pixelsamples" [ $SPP ]
Integrator "path" "integer maxdepth" [ 1 ]
Film "rgb" "integer xresolution" [ 16 ] "integer yresolution" [ 16 ] "string filename" [ "$OUT/$name-pbrt.exr" ]
PixelFilter "box"
WorldBegin
LightSource "infinite" "rgb L" [ 1 1 1 ]
$material
Shape "trianglemesh" "point3 P" [ -1000 -1000 0  1000 -1000 0  1000 1000 0  -1000 1000 0 ]
  "integer indices" [ 0 1 2  0 2 3 ]
SCENE
      "$LANTERN" render "$OUT/$name.pbrt" --quiet -o "$OUT/$name-lantern.exr" > /dev/null
      l=$(mean "$OUT/$name-lantern.exr")
      p="-"; ratio="-"
      if [ -n "$PBRT" ]; then
        "$PBRT" --quiet "$OUT/$name.pbrt" > /dev/null
        p=$(mean "$OUT/$name-pbrt.exr")
        ratio=$("$LANTERN" compare "$OUT/$name-lantern.exr" "$OUT/$name-pbrt.exr" | awk '/^ratio /{printf "%.3f %.3f %.3f", $2, $3, $4}')
      fi
      printf "%-5s %-13s %-5s | %-22s | %-22s | %s\n" "$rough" "$refl" "$theta" "$l" "$p" "$ratio"
    done
  done
done
