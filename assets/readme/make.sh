#!/usr/bin/env bash
# Rebuilds the README pictures in assets/readme/ from the current renderer.
#
#   assets/readme/make.sh [CITYSPEC_BINARY]     (default: target/release/cityspec)
#
# Needs ImageMagick's `convert` (apt-get install imagemagick) to scale and JPEG-encode.
# Builds into $WORK (default /dev/shm/readme-pictures, cached between runs):
#   day-layout.png, day-plan.png, day-overview.jpg, day-street.jpg   specs/day.toml
#   night-street.jpg                                                   specs/night.toml
#   closeups.jpg        day and night street frames 75, 32 / 75, 50 in a 2 × 2 grid
#   sign-faces.jpg      the sign-face contact sheet of `cargo test --lib contact_sheet`
#   text-street.jpg                                                    specs/text.toml (words camera)
#   osm-overview.jpg, osm-street.jpg   specs/osm.toml: its overview, and the first rows of its
#       street (top) and walk (bottom) camera previews
#   street-{noon,overcast,fog,rain,dusk,night}.png                     frame $FRAME of
#       specs/fog.toml's street path with only `[weather] kind` and `[lighting] time`
#       changed, so all six show one viewpoint.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
bin="${1:-$repo/target/release/cityspec}"
work="${WORK:-/dev/shm/readme-pictures}"
frame="${FRAME:-000010}"
if ! convert -version 2>/dev/null | grep -q ImageMagick; then
    echo "make.sh: needs ImageMagick's convert (apt-get install imagemagick)" >&2
    exit 1
fi
mkdir -p "$work/specs"
build() { "$bin" build -q --out "$work/out" --cache "$work/cache" "$@"; }

build "$repo/specs/day.toml" "$repo/specs/night.toml" "$repo/specs/text.toml"
cp "$work/out/day/layout.png" "$here/day-layout.png"
cp "$work/out/day/plan.png" "$here/day-plan.png"
convert "$work/out/day/overview.png" -resize 800x -strip -quality 85 "$here/day-overview.jpg"
convert "$work/out/day/frames/street/preview.png" -resize 800x -strip -quality 85 "$here/day-street.jpg"
convert "$work/out/night/frames/street/preview.png" -resize 800x -strip -quality 85 "$here/night-street.jpg"
convert "$work/out/text/frames/words/preview.png" -resize 800x -strip -quality 85 "$here/text-street.jpg"
rgb() { echo "$work/out/$1/frames/street/rgb/$2.png"; }
convert \( "$(rgb day 000075)" "$(rgb day 000032)" +append \) \
    \( "$(rgb night 000075)" "$(rgb night 000050)" +append \) -append \
    -resize 800x -strip -quality 85 "$here/closeups.jpg"
build "$repo/specs/osm.toml"
convert "$work/out/osm/overview.png" -resize 640x -strip -quality 85 "$here/osm-overview.jpg"
first_row() { convert "$work/out/osm/frames/$1/preview.png" -crop 100%x25%+0+0 +repage png:-; }
convert <(first_row street) <(first_row walk) -append -strip -quality 85 "$here/osm-street.jpg"
(cd "$repo" && CITYSPEC_SIGN_SHEET="$work/sign-faces.png" cargo test -q --lib contact_sheet >/dev/null)
convert "$work/sign-faces.png" -resize 800x -strip -quality 85 "$here/sign-faces.jpg"

# The condition row: fog.toml with its weather kind and lighting time swapped.
for cond in noon:clear:day overcast:overcast:day fog:fog:day rain:rain:day dusk:clear:dusk night:clear:night; do
    IFS=: read -r name weather time <<<"$cond"
    sed -e "s/^name = \"fog\"/name = \"street-$name\"/" \
        -e "s/^kind = \"fog\"/kind = \"$weather\"/" \
        -e "s/^time = \"day\"/time = \"$time\"/" \
        -e "s#\"\.\./assets/#\"$repo/assets/#" \
        "$repo/specs/fog.toml" >"$work/specs/street-$name.toml"
    build "$work/specs/street-$name.toml"
    convert "$work/out/street-$name/frames/street/rgb/$frame.png" -resize 320x240 -strip -define png:exclude-chunks=date,time "$here/street-$name.png"
done
echo "pictures written to $here"
