#!/usr/bin/python3
"""Camera noise for a biref picture: camera_noise.py IN.png OUT.png SIGMA [SEED]. Reads an 8-bit RGB
PNG (as biref writes it), adds Gaussian noise of SIGMA (in 8-bit steps, seeded), rounds, clips and
writes an 8-bit RGB PNG. PNG decoding and encoding by hand (zlib, the five filters): numpy only."""
import sys, zlib, struct
import numpy as np
def read_png_rgb8(path):
    data = open(path, "rb").read(); pos = 8; idat = b""; w = h = 0
    while pos < len(data):
        ln, typ = struct.unpack(">I4s", data[pos:pos + 8]); body = data[pos + 8:pos + 8 + ln]; pos += 12 + ln
        if typ == b"IHDR": w, h, bd, ct = struct.unpack(">IIBB", body[:10]); assert bd == 8 and ct == 2
        elif typ == b"IDAT": idat += body
    raw = zlib.decompress(idat); st = 3 * w; out = np.zeros((h, st), np.uint8); prev = np.zeros(st, np.int32)
    for y in range(h):
        f = raw[y * (st + 1)]; line = np.frombuffer(raw[y * (st + 1) + 1:(y + 1) * (st + 1)], np.uint8).astype(np.int32); cur = np.zeros(st, np.int32)
        for x in range(st):
            a = cur[x - 3] if x >= 3 else 0; b = prev[x]; c = prev[x - 3] if x >= 3 else 0
            p = {0: 0, 1: a, 2: b, 3: (a + b) // 2}.get(f)
            if f == 4:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c); p = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
            cur[x] = (line[x] + p) & 255
        out[y] = cur; prev = cur
    return out.reshape(h, w, 3)
def write_png_rgb8(path, img):
    h, w, _ = img.shape; raw = b"".join(b"\0" + img[y].tobytes() for y in range(h))
    chunk = lambda t, b: struct.pack(">I", len(b)) + t + b + struct.pack(">I", zlib.crc32(t + b) & 0xffffffff)
    open(path, "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
img = read_png_rgb8(sys.argv[1]).astype(float)
rng = np.random.default_rng(int(sys.argv[4]) if len(sys.argv) > 4 else 1)
noisy = np.clip(np.round(img + rng.normal(0, float(sys.argv[3]), img.shape)), 0, 255).astype(np.uint8)
write_png_rgb8(sys.argv[2], noisy)
