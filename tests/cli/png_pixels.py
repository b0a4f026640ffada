"""Pixels of an 8-bit RGB or RGBA PNG, without libraries beyond the standard ones.

  png_pixels.py FILE X Y                 prints the pixel at (X, Y) (top-left origin) as "R G B"
  png_pixels.py FILE --differing R G B   prints how many pixels differ from R G B by more than 8
"""
import struct
import sys
import zlib


def read_png(path):
    data = open(path, 'rb').read()
    if data[:8] != b'\x89PNG\r\n\x1a\n':
        sys.exit(f'{path}: not a PNG')
    pos, idat, width, height, channels = 8, b'', 0, 0, 0
    while pos < len(data):
        length, kind = struct.unpack('>I4s', data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b'IHDR':
            width, height, depth, color = struct.unpack('>IIBB', body[:10])
            if depth != 8 or color not in (2, 6) or body[12] != 0:
                sys.exit(f'{path}: only 8-bit RGB/RGBA, not interlaced')
            channels = 3 if color == 2 else 4
        elif kind == b'IDAT':
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, prev = [], bytearray(stride)
    for y in range(height):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = prev[i]
            c = prev[i - channels] if i >= channels else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pred) & 255
        rows.append(line)
        prev = line
    return width, height, channels, rows


def main():
    width, height, channels, rows = read_png(sys.argv[1])
    if sys.argv[2] == '--differing':
        ref = [int(v) for v in sys.argv[3:6]]
        n = 0
        for line in rows:
            for x in range(width):
                px = line[x * channels:x * channels + 3]
                n += any(abs(px[k] - ref[k]) > 8 for k in range(3))
        print(n)
    else:
        x, y = int(sys.argv[2]), int(sys.argv[3])
        print(' '.join(str(v) for v in rows[y][x * channels:x * channels + 3]))


if __name__ == '__main__':  # also imported by tests/view/browser_test.py
    main()
