#!/usr/bin/python3
"""Writes a scene folder at twice the size of another: each pixel of depth.pfm (and of
depth_reversed.pfm and normals.pfm, where present) repeated over 2x2 pixels, camera.json with its
width and height doubled (the projection is the same). For timings at a larger size of the same
content (docs/reuse-measured.md: street_track at 1920x1080 on a GPU).

usage: tools/scene-double.py SRC_DIR DST_DIR
"""
import json, os, sys

import numpy as np


def read_pfm(path):
    with open(path, 'rb') as f:
        kind = f.readline().strip()
        w, h = (int(x) for x in f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype='<f4' if scale < 0 else '>f4')
    return kind, data.reshape((h, w, 3) if kind == b'PF' else (h, w))


def write_pfm(path, kind, data):
    with open(path, 'wb') as f:
        f.write(kind + b'\n%d %d\n-1.0\n' % (data.shape[1], data.shape[0]))
        f.write(np.ascontiguousarray(data, dtype='<f4').tobytes())


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    src, dst = sys.argv[1:]
    if not os.path.isfile(os.path.join(src, 'depth.pfm')) or not os.path.isfile(os.path.join(src, 'camera.json')):
        sys.exit('%s: no depth.pfm and camera.json' % src)
    os.makedirs(dst, exist_ok=True)
    for name in ('depth.pfm', 'depth_reversed.pfm', 'normals.pfm'):
        path = os.path.join(src, name)
        if os.path.isfile(path):
            kind, data = read_pfm(path)
            write_pfm(os.path.join(dst, name), kind, np.repeat(np.repeat(data, 2, axis=0), 2, axis=1))
    camera = json.load(open(os.path.join(src, 'camera.json')))
    camera['width'], camera['height'] = 2 * camera['width'], 2 * camera['height']
    with open(os.path.join(dst, 'camera.json'), 'w') as f:
        json.dump(camera, f, indent=2)
    print('wrote', dst)


if __name__ == '__main__':
    main()
