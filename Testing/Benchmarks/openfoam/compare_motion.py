"""Checks that moveMesh and MLS Deform made the same motion (run-openfoam-benchmark.sh, untimed):
reads the double points of the source case, of moveMesh's time 1 and of MLS Deform's first
variant, and prints the hull's largest error against the translation for both tools and how far
apart their displacements are elsewhere, relative to the translation's length.
Usage: pvpython compare_motion.py SOURCE_CASE MOVEMESH_CASE MLS_CASE DX,DY,DZ"""
import re
import sys

import numpy as np

source, moved, variant = sys.argv[1:4]
translation = np.array([float(v) for v in sys.argv[4].split(',')])


def foam_list(data, start, dtype, width):
    """The binary OpenFOAM list after offset start: (n x width array, offset after it)."""
    m = re.compile(rb'\n(\d+)\s*\n?\(').search(data, start)
    n = int(m.group(1))
    end = m.end() + n * width * np.dtype(dtype).itemsize
    values = np.frombuffer(data[m.end():end], dtype=dtype)
    return (values.reshape(n, width) if width > 1 else values), end


def read(path):
    global binary
    data = open(path, 'rb').read()
    header = data.index(b'}', data.index(b'FoamFile'))
    binary = re.search(rb'format\s+binary', data[:header]) is not None
    return data, header


def points(case_polymesh):
    data, header = read(case_polymesh + '/points')
    if binary:
        return foam_list(data, header, '<f8', 3)[0]
    body = data[header:].decode()
    number = r'([-+0-9.eE]+)'
    rows = re.findall(r'\(%s %s %s\)' % (number, number, number), body)
    return np.array(rows, dtype=float)


def hull_points(polymesh):
    boundary = open(polymesh + '/boundary').read()
    m = re.search(r'\bhull\s*\{[^}]*?nFaces\s+(\d+);\s*startFace\s+(\d+);', boundary, re.S)
    count, first = int(m.group(1)), int(m.group(2))
    data, header = read(polymesh + '/faces')
    if binary:  # faceCompactList: offsets, then the labels (label=32)
        offsets, end = foam_list(data, header, '<i4', 1)
        labels, _ = foam_list(data, end, '<i4', 1)
        return np.unique(labels[offsets[first]:offsets[first + count]])
    faces = re.findall(r'\d+\(([\d ]+)\)', data[header:].decode())
    return np.unique([int(v) for f in faces[first:first + count] for v in f.split()])


binary = False
rest = points(source + '/constant/polyMesh')
hull = hull_points(source + '/constant/polyMesh')
length = np.linalg.norm(translation)
d_move = points(moved + '/1/polyMesh') - rest
d_mls = points(variant + '/constant/polyMesh') - rest
apart = np.linalg.norm(d_move - d_mls, axis=1) / length
print('Same motion? Hull (%d points): largest error / |translation| moveMesh %.1e, MLS Deform %.1e; '
      'their displacements apart / |translation|: mean %.3f, 95th percentile %.3f, max %.3f'
      % (len(hull), np.abs(d_move[hull] - translation).max() / length, np.abs(d_mls[hull] - translation).max() / length,
         apart.mean(), np.percentile(apart, 95), apart.max()))
