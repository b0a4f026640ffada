#!/usr/bin/env bash
# The videos simbob writes, as FFmpeg's own ffprobe sees them: codec, size, frame rate and the
# number of frames counted by decoding. Usage: ffprobe.sh WRITER (build/tests/simbob_write_test_video).
# Exits 77 (skipped) when ffprobe is not installed.
set -euo pipefail
writer=$1
if ! command -v ffprobe >/dev/null; then
  echo "SKIP: ffprobe is not installed (Debian package ffmpeg)"
  exit 77
fi
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail=0
check() {  # FILE FRAMES FPS EXPECTED
  "$writer" "$dir/$1" "$2" "$3"
  got=$(ffprobe -v error -count_frames -select_streams v:0 \
    -show_entries stream=codec_name,width,height,avg_frame_rate,nb_read_frames -of csv=p=0 "$dir/$1")
  if [[ "$got" != "$4" ]]; then
    echo "FAIL: $1: ffprobe says '$got', expected '$4'"
    fail=1
  else
    echo "ok: $1: $got"
  fi
}
check a.avi 12 10 "mjpeg,160,120,10/1,12"
check b.mp4 12 10 "h264,160,120,10/1,12"
check c.avi 7 25 "mjpeg,160,120,25/1,7"
check d.mp4 30 30 "h264,160,120,30/1,30"
exit $fail
