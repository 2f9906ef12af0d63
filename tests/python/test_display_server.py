"""`lantern render --display-server HOST:PORT` against a small server that
speaks tev's protocol on 127.0.0.1: the stream holds one CreateImage, then
UpdateImageV3 bands, and the last update of every row is the image the
render wrote, bit for bit."""
import socket
import struct
import subprocess
import threading

import numpy as np

import lantern


def read_string(data, pos):
    end = data.index(b"\0", pos)
    return data[pos:end].decode(), end + 1


def parse(stream):
    """The packets as (type, fields) tuples."""
    packets, pos = [], 0
    while pos < len(stream):
        (length,) = struct.unpack_from("<I", stream, pos)
        kind, body, p = stream[pos + 4], stream[pos:pos + length], 5
        if kind == 4:  # CreateImage
            p += 1
            name, p = read_string(body, p)
            width, height, channels = struct.unpack_from("<iii", body, p)
            p += 12
            names = []
            for _ in range(channels):
                n, p = read_string(body, p)
                names.append(n)
            packets.append((4, dict(name=name, width=width, height=height, channels=names)))
        elif kind == 6:  # UpdateImageV3
            p += 1
            name, p = read_string(body, p)
            (channels,) = struct.unpack_from("<i", body, p)
            p += 4
            for _ in range(channels):
                _, p = read_string(body, p)
            x, y, w, h = struct.unpack_from("<iiii", body, p)
            p += 16
            offsets = struct.unpack_from(f"<{channels}q", body, p)
            strides = struct.unpack_from(f"<{channels}q", body, p + 8 * channels)
            p += 16 * channels
            floats = np.frombuffer(body, dtype="<f4", offset=p)
            assert len(floats) == max(o + (w * h - 1) * s + 1 for o, s in zip(offsets, strides))
            planes = [floats[o::s][: w * h] for o, s in zip(offsets, strides)]
            packets.append((6, dict(name=name, x=x, y=y, w=w, h=h, rgb=np.stack(planes, axis=1).reshape(h, w, 3))))
        else:
            raise AssertionError(f"unexpected packet type {kind}")
        pos += length
    return packets


def test_the_display_server_receives_the_whole_image(lantern_binary, source_dir, tmp_path):
    server = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    server.bind(("127.0.0.1", 0))
    server.listen(1)
    server.settimeout(60)  # a lantern that never connects fails the test, not hangs it
    port = server.getsockname()[1]
    stream = bytearray()

    def serve():
        conn, _ = server.accept()
        with conn:
            while chunk := conn.recv(1 << 16):
                stream.extend(chunk)

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    out = tmp_path / "shown.exr"
    subprocess.run([lantern_binary, "render", str(source_dir / "scenes" / "cornell-box.pbrt"), "--spp", "32",
                    "--resolution", "64", "48", "-q", "-o", str(out), "--display-server", f"127.0.0.1:{port}"],
                   check=True, timeout=120)
    thread.join(30)
    server.close()
    packets = parse(bytes(stream))
    assert packets[0] == (4, dict(name=str(out), width=64, height=48, channels=["R", "G", "B"]))
    updates = [p for kind, p in packets if kind == 6]
    # Two passes of 16 samples (shown as the display thread gets to them: at
    # least once, however fast the render), then the finished image.
    assert len(updates) >= 2
    shown = np.zeros((48, 64, 3), dtype=np.float32)
    for u in updates:
        shown[u["y"]:u["y"] + u["h"], u["x"]:u["x"] + u["w"]] = u["rgb"]
    assert np.array_equal(shown, lantern.read_image(str(out)))


def test_an_unreachable_display_server_is_a_warning(lantern_binary, source_dir, tmp_path):
    probe = socket.socket()
    probe.bind(("127.0.0.1", 0))
    port = probe.getsockname()[1]
    probe.close()  # nothing listens there now
    out = tmp_path / "alone.exr"
    done = subprocess.run([lantern_binary, "render", str(source_dir / "scenes" / "cornell-box.pbrt"), "--spp", "1",
                           "--resolution", "16", "16", "-q", "-o", str(out), "--display-server", f"127.0.0.1:{port}"],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0 and out.exists()
    assert "display server 127.0.0.1:" in done.stderr and "rendering without it" in done.stderr
