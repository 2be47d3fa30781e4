# Helpers shared by the scripts that make the docs' pictures in the real MeshLab GUI (sourced;
# they expect $here, the repository, and $out, a working folder).
# view(out.png, dy, wheel, files...): MeshLab showing FILES with the trackball hidden, turned by
# dragging dy px up (negative: down) and zoomed by wheel steps; cropped to the view.
view() {
  local shot="$1" dy="$2" wh="$3"; shift 3
  { echo "sleep 2"; echo "click 231 10"; echo "sleep 1"; echo "click 290 113"; echo "sleep 1"; [ "$dy" != 0 ] && echo "drag 430 560 430 $((560 - dy))"; [ "$wh" != 0 ] && echo "wheel 430 420 $wh"
    echo "sleep 4"; echo "shot $shot"; } >"$out/view.txt"
  "$here/scripts/gui-shots.sh" "$out/view.txt" -- "$@" >/dev/null
  convert "$shot" -crop 760x660+40+100 +repage "$shot"
}
# label(picture, text): a caption above the picture.
label() { convert "$1" -gravity north -background white -splice 0x34 -font DejaVu-Sans -pointsize 22 -annotate +0+4 "$2" "$1"; }
