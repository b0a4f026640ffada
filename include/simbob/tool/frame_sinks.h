// Where recorded frames go (issue #12): a numbered PNG sequence, one video file, or either of
// them fed from a worker thread so that encoding overlaps rendering and physics.
//
// Output discipline, as for every simbob output: nothing under a final name is replaced or left
// half-written by a failed run.
//  - PNG sequence: frames are written into a staging directory DIR/.simbob-frames.tmp.<pid>/ and
//    moved to DIR/frame_000000.png, ... only by a successful finish(), which then also removes
//    higher-numbered frame_NNNNNN.png left in DIR by an earlier, longer recording (so DIR never
//    mixes two recordings). A failed or abandoned recording removes its staging directory and
//    leaves DIR as it was (a DIR the sink created is removed again).
//  - Video: the bytes go to "<path>.tmp.<pid>" beside path and are renamed over it by finish(),
//    or, given a file to write to, are left there for the caller to commit with its other outputs.
//
// Determinism: the same frames give the same bytes. PNGs always; AVI/MJPEG always (bit-exact
// flags, no encoder version strings); MP4/H.264 through libx264 with one thread and bit-exact
// flags (same libx264 build -> same bytes; another x264 version may encode differently).
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "simbob/error.h"
#include "simbob/image.h"

namespace simbob {

/// Frames as DIR/frame_000000.png, DIR/frame_000001.png, ... (6 digits, more past 999999).
/// DIR is created if missing. Null and *err (CannotCreate) when DIR cannot be created or
/// written, or is not a directory.
std::unique_ptr<FrameSink> makePngSequenceSink(const std::string& dir, Error* err);

/// Whether a file called `name` in DIR is one the PNG sequence writes or, as a frame of an
/// earlier recording, removes: "frame_" + six or more digits + ".png".
bool isFrameFileName(const std::string& name);

/// One video at `path`, chosen by its extension (case-insensitive): ".avi" = Motion JPEG in AVI
/// (what the original Simulator Bob wrote), ".mp4" = H.264 in MP4 (libx264, else another H.264
/// encoder of the installed libavcodec). `fps` frames per second (0 < fps <= 1000). The size is
/// that of the first frame; every frame must have it, and width and height must be even for
/// H.264. Null and *err when the extension is unknown (InvalidInput), the codec is missing
/// (CannotCreate, naming it) or the file cannot be created (CannotCreate).
/// With `write_to` (the temporary file of an OutputFile for `path`), the bytes go there and
/// finish() leaves them there: the caller commits them with the run's other outputs
/// (commitOutputs), so that a run that fails after the video was finished publishes none of it.
std::unique_ptr<FrameSink> makeVideoSink(const std::string& path, double fps, Error* err,
                                         const std::string& write_to = "");

/// What makeVideoSink would use for path's extension: "mjpeg", "libx264", another encoder's
/// name, or "" (and *why) when there is none.
std::string videoEncoderFor(const std::string& path, std::string* why);

/// Feeds every sink in `sinks`, in order, from one worker thread through a queue of at most
/// `queue_frames` frames: add() returns as soon as the frame is queued (it waits only while the
/// queue is full). The first error of any sink stops the recording: it is returned by the next
/// add() or by finish(), and the other sinks are abandoned (their outputs are not committed).
/// finish() waits for the queue to drain and then finishes the sinks in order; if one of those
/// finish() calls fails, the sinks after it are abandoned but those before it stay committed.
/// Destroying it without finish() stops the worker and abandons every sink.
std::unique_ptr<FrameSink> makeAsyncSink(std::vector<std::unique_ptr<FrameSink>> sinks, size_t queue_frames = 4);

}  // namespace simbob
