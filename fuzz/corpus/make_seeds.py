#!/usr/bin/env python3
"""Writes the fuzz seed corpora: small valid inputs of every form each reader
accepts (and a few it refuses), so that fuzzing starts from deep inside the
formats rather than rediscovering their magic numbers. Standard library only.
Run from anywhere: python3 fuzz/corpus/make_seeds.py"""
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def write(kind, name, data):
    os.makedirs(os.path.join(HERE, kind), exist_ok=True)
    with open(os.path.join(HERE, kind, name), "wb") as f:
        f.write(data)


def chunk(tag, body):
    return struct.pack(">I", len(body)) + tag + body + struct.pack(">I", zlib.crc32(tag + body) & 0xFFFFFFFF)


def png(width, height, color_type, depth, rows, interlace=0, palette=None, trns=None):
    ihdr = struct.pack(">IIBBBBB", width, height, depth, color_type, 0, 0, interlace)
    out = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr)
    if palette:
        out += chunk(b"PLTE", palette)
    if trns:
        out += chunk(b"tRNS", trns)
    raw = b"".join(b"\x00" + r for r in rows)  # filter type 0 (None) on every row
    return out + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")


def pngs():
    write("png", "gray8_3x2.png", png(3, 2, 0, 8, [bytes([0, 128, 255]), bytes([10, 20, 30])]))
    write("png", "gray16_2x2.png", png(2, 2, 0, 16, [b"\x00\x00\xff\xff", b"\x12\x34\x80\x00"]))
    write("png", "gray1_9x2.png", png(9, 2, 0, 1, [b"\xa5\x80", b"\x0f\x00"]))
    write("png", "rgb8_2x2.png", png(2, 2, 2, 8, [bytes(range(6)), bytes(range(100, 106))]))
    write("png", "rgb16_1x2.png", png(2, 1, 2, 16, [bytes(range(12))]))
    write("png", "rgba8_2x1.png", png(2, 1, 6, 8, [bytes([1, 2, 3, 255, 4, 5, 6, 0])]))
    write("png", "graya8_2x1.png", png(2, 1, 4, 8, [bytes([7, 255, 8, 128])]))
    write("png", "palette4_3x1.png", png(3, 1, 3, 4, [b"\x01\x20"], palette=bytes(range(9)), trns=b"\x80"))
    rows = [bytes([(x * 16 + y) % 256 for x in range(8)]) for y in range(8)]
    write("png", "gray8_8x8_interlaced.png", png(8, 8, 0, 8, rows, interlace=1))


def npy(descr, shape, data, fortran=False, major=1, quote="'"):
    shape_text = "(" + ", ".join(str(d) for d in shape) + ("," if len(shape) == 1 else "") + ")"
    header = "{%sdescr%s: %s%s%s, %sfortran_order%s: %s, %sshape%s: %s, }" % (
        quote, quote, quote, descr, quote, quote, quote, "True" if fortran else "False", quote, quote, shape_text)
    length_bytes = 2 if major == 1 else 4
    total = 8 + length_bytes + len(header) + 1
    header += " " * ((64 - total % 64) % 64) + "\n"
    length = struct.pack("<H" if major == 1 else "<I", len(header))
    return b"\x93NUMPY" + bytes([major, 0]) + length + header.encode("latin1") + data


def npys():
    write("npy", "f4_2x3.npy", npy("<f4", (2, 3), struct.pack("<6f", 0, 0.25, 0.5, 0.75, 1, 0.1)))
    write("npy", "f8_2x2x3_fortran.npy", npy("<f8", (2, 2, 3), struct.pack("<12d", *[i / 12 for i in range(12)]), True))
    write("npy", "u1_3x4.npy", npy("|u1", (3, 4), bytes(range(0, 240, 20))))
    write("npy", "u2_big_endian_2x2x4.npy", npy(">u2", (2, 2, 4), struct.pack(">16H", *range(0, 65536, 4096))))
    write("npy", "f4_1x1x1_v2.npy", npy("<f4", (1, 1, 1), struct.pack("<f", 0.5), major=2))
    write("npy", "f4_1x2_v3_double_quotes.npy", npy("<f4", (1, 2), struct.pack("<2f", 0.5, 1), major=3, quote='"'))
    write("npy", "refused_i4.npy", npy("<i4", (2, 2), bytes(16)))
    write("npy", "refused_rank1.npy", npy("<f4", (4,), bytes(16)))


def argvs():
    seeds = {
        "fuse_wavelet": ["fuse", "--method", "wavelet", "--wavelet", "bior4.4", "--levels", "3", "--mode",
                         "symmetric", "--base-rule", "mean", "--detail-rule", "max-abs", "-o", "out.npy", "a.png",
                         "b.npy"],
        "fuse_equals": ["fuse", "--method=laplacian", "--levels=4", "--backend=cpu", "--output=x.png", "--", "-a.png"],
        "fuse_channel_sum": ["fuse", "--method", "channel-sum", "-o", "o.png", "r.png", "g.png", "b.png"],
        "fuse_bad_levels": ["fuse", "--method", "laplacian", "--levels", "3x", "-o", "o.npy", "a.npy"],
        "metrics": ["metrics", "--background", "bg.png", "--backend", "vulkan", "a.png", "b.npy"],
        "info": ["info"],
        "run": ["run", "--sensors", "2", "--sequence", "15,15,15+0,15,0", "--method", "wavelet", "--cycles", "5",
                "--virtual-clock", "--background-frames", "3", "--timeout", "2.5", "--out", "out"],
        "run_replay": ["run", "--replay", "data", "--duration", "1e-3", "--object", "coin"],
        "sim_help": ["sim", "--help"],
        "fuse_missing_value": ["fuse", "--method"],
    }
    for name, words in seeds.items():
        write("args", name, b"\x00".join(w.encode() for w in words))


pngs()
npys()
argvs()
