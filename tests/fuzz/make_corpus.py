#!/usr/bin/python3
"""Writes the fuzz harnesses' seed corpora, tests/fuzz/corpus/<harness>/: a few small
valid inputs each, made from the committed test data (tests/data) or written here.
Run from the repository root with Debian's python3 (numpy, python3-opencv):
    /usr/bin/python3 tests/fuzz/make_corpus.py
The fuzzers never write the committed corpus (scripts/fuzz.sh runs on a copy)."""
import json
import os
import shutil
import struct
import tempfile

import cv2
import numpy as np

C = 'tests/fuzz/corpus'
D = 'tests/data'
TMP = tempfile.mkdtemp()


def w(name, data):
    path = os.path.join(C, name)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, 'wb') as f:
        f.write(data)


def read(path):
    with open(path, 'rb') as f:
        return f.read()


def png(name, image):
    path = os.path.join(TMP, 'image.png')
    cv2.imwrite(path, image)
    w(name, read(path))


# PFM: gray little-endian with an unknown (+inf), colour big-endian, one pixel.
a = np.arange(12, dtype='<f4').reshape(3, 4)
a[1, 2] = np.inf
w('pfm/gray_le.pfm', b'Pf\n4 3\n-1.0\n' + a[::-1].tobytes())
b = np.arange(12, dtype='>f4').reshape(2, 2, 3)
w('pfm/color_be.pfm', b'PF\n2 2\n1.0\n' + b[::-1].tobytes())
w('pfm/one_pixel.pfm', b'Pf\n1 1\n-0.5\n' + np.array([3.5], dtype='<f4').tobytes())

# Calibration: Middlebury (short and with the optional keys), KITTI 2012 and 2015 names.
w('calibration/middlebury_teddyh.txt', read(f'{D}/TeddyH/calib.txt'))
w('calibration/middlebury_full.txt', read(f'{D}/calib/middeval3_motorcycle_Q.txt'))
w('calibration/kitti2012.txt', read(f'{D}/calib/kitti2012_000070.txt'))
kitti = read(f'{D}/calib/kitti2012_000070.txt').decode().splitlines()
w('calibration/kitti2015_rect.txt',
  ('\n'.join(line.replace('P0:', 'P_rect_00:').replace('P1:', 'P_rect_01:') for line in kitti[:2]) +
   '\n').encode())

# OpenCV stereo calibration: Q (as cv::stereoRectify writes it), unit, image size.
Q = np.array([[1, 0, 0, -99.5], [0, 1, 0, -93.5], [0, 0, 0, 750], [0, 0, 1 / 80., 0]])
for ext in ('yml', 'xml'):
    path = os.path.join(TMP, f'stereo.{ext}')
    fs = cv2.FileStorage(path, cv2.FILE_STORAGE_WRITE)
    fs.write('Q', Q)
    fs.write('unit', 'mm')
    fs.write('image_width', 225)
    fs.write('image_height', 187)
    fs.release()
    w(f'opencv_camera/stereo.{ext}', read(path))
path = os.path.join(TMP, 'stereo_m.yml')
fs = cv2.FileStorage(path, cv2.FILE_STORAGE_WRITE)
fs.write('Q', Q)
fs.write('unit', 'm')
fs.write('image_size', np.array([225, 187], dtype=np.int32))
fs.release()
w('opencv_camera/stereo_size_m.yml', read(path))

# pick's calibration against its pair's size: width, height (uint16 little-endian), the
# file's format (0 calib.txt, 1 .yml, 2 .xml), then the file. The pair's own size, the
# size halved (a uniform resize) and one that is not a resize.
teddy = read(f'{D}/TeddyH/calib.txt')
for name, (width, height), kind, body in [
        ('teddyh_own_size', (225, 187), 0, teddy),
        ('teddyh_halved', (112, 93), 0, teddy),
        ('teddyh_not_a_resize', (225, 100), 0, teddy),
        ('opencv_yml', (225, 187), 1, read('tests/fuzz/corpus/opencv_camera/stereo.yml')),
        ('opencv_xml_doubled', (450, 374), 2, read('tests/fuzz/corpus/opencv_camera/stereo.xml'))]:
    w(f'pick_calibration/{name}', struct.pack('<HHB', width, height, kind) + body)

# KITTI 16-bit disparities, one with no-data pixels.
d = np.arange(48, dtype=np.uint16).reshape(6, 8) * 300
d[0, 0] = 0
png('kitti_disparity/small.png', d)
png('kitti_disparity/max.png', np.full((2, 3), 65535, np.uint16))

# Middlebury v2: 8-bit gray, three equal channels, a mask.
g = np.arange(48, dtype=np.uint8).reshape(6, 8) * 5
g[2, 3] = 0
png('middlebury_v2/gray.png', g)
png('middlebury_v2/equal_rgb.png', cv2.merge([g, g, g]))
png('middlebury_v2/mask.png', np.where(g > 100, 255, 0).astype(np.uint8))

# Command lines, one token a line.
for name, tokens in {
        'stereo_defaults': ['left.png', 'right.png', '-o', 'disp.pfm'],
        'stereo_params': ['left.png', 'right.png', '--ndisp', '64', '--seed', '7', '--tau-color', '10.5',
                          '--threads', '2', '--method', 'pms', '--quiet'],
        'opencv_method': ['--method', 'sgbm', '--ndisp', '96', '-o', 'out.pfm', '--count', '12'],
        'help': ['--help'],
        'unknown': ['a', '--scale', '0.5', '--bogus', 'x'],
}.items():
    w(f'cli/{name}.txt', '\n'.join(tokens).encode())

# A BOP scene's three JSON files cut by NUL bytes (and without scene_gt_info.json).
scene = f'{D}/bop_tless_like/000001'
parts = [read(f'{scene}/{f}') for f in ('scene_camera.json', 'scene_gt.json', 'scene_gt_info.json')]
w('bop_json/tless_like.bin', b'\0'.join(parts))
w('bop_json/tless_like_no_gt_info.bin', b'\0'.join(parts[:2]))
# The poses' kinds the readers tell apart (host/io/physical_checks.h): image 0 pasted
# (pose_unknown, the origin), image 1 flipped once (a reflected R); a part without pixels.
kinds = [parts[0].replace(b'"elev": 30', b'"elev": 30, "pose_unknown": true')
                 .replace(b'"elev": 35', b'"elev": 35, "flip_horizontal": true'),
         parts[1].replace(b'[-13.0, -8.5, 600.0]', b'[0.0, 0.0, 0.0]')
                 .replace(b'0.0, -1.0], "cam_t_m2c": [4.0', b'0.0, 1.0], "cam_t_m2c": [4.0'),
         parts[2].replace(b'"bbox_visib": [9, 7, 13, 11]', b'"bbox_visib": [-1, -1, -1, -1]')]
assert kinds != parts
w('bop_json/pasted_flipped_hidden.bin', b'\0'.join(kinds))

# COCO: two images of the committed synthetic set (compressed RLE), a crowd region
# (uncompressed RLE).
coco = json.loads(read(f'{D}/detect/tless_synth_8/coco_instances.json'))
ids = {coco['images'][0]['id'], coco['images'][1]['id']}
w('coco/two_images.json', json.dumps({
    'images': coco['images'][:2],
    'annotations': [a for a in coco['annotations'] if a['image_id'] in ids][:3],
    'categories': coco['categories']}).encode())
w('coco/crowd_uncompressed.json', json.dumps({
    'images': [{'id': 5, 'file_name': 'a.png', 'width': 4, 'height': 3}],
    'annotations': [{'id': 1, 'image_id': 5, 'category_id': 1, 'bbox': [0, 0, 2, 3], 'area': 6, 'iscrowd': 1,
                     'segmentation': {'size': [3, 4], 'counts': [0, 6, 6]}}],
    'categories': [{'id': 1, 'name': 'obj_01'}]}).encode())

# Detection results against tests/data/detect/tless_synth_8, COCO and BOP forms.
images = {i['id']: i for i in coco['images']}
boxes = coco['annotations'][:2]
w('detection_results/coco_form.json', json.dumps(
    [{'image_id': a['image_id'], 'category_id': a['category_id'], 'bbox': a['bbox'], 'score': 0.9}
     for a in boxes]).encode())
w('detection_results/bop_form.json', json.dumps(
    [{'scene_id': images[a['image_id']]['scene_id'], 'image_id': images[a['image_id']]['im_id'],
      'category_id': a['category_id'], 'bbox': a['bbox'], 'score': 0.5, 'time': 0.1} for a in boxes]).encode())
w('detection_results/empty.json', b'[]')

# BOP pose results.
w('bop_pose_results/with_header.csv',
  b'scene_id,im_id,obj_id,score,R,t,time\n1,0,5,0.75,1 0 0 0 1 0 0 0 1,10 -20 500.5,0.25\n'
  b'1,3,7,1,0 -1 0 1 0 0 0 0 1,0 0 300,-1\n')
w('bop_pose_results/failed_estimate_at_origin.csv',
  b'scene_id,im_id,obj_id,score,R,t,time\n1,0,5,0,1 0 0 0 1 0 0 0 1,0 0 0,-1\n')
w('bop_pose_results/no_header_crlf.csv',
  b'2,1,1,0.5,1 0 0 0 1 0 0 0 1,1 2 3,1.5\r\n\r\n2,1,4,0.25,1 0 0 0 0 -1 0 1 0,4 5 6,1.5')

# Meshes: the first byte picks the extension (0 .stl, 1 .ply, 2 .obj).
for first, name in ((0, 'cube.stl'), (0, 'cube_ascii.stl'), (1, 'cube_smooth_normals.ply'), (2, 'cube.obj')):
    w(f'mesh/{name}', bytes([first]) + read(f'{D}/render/{name}'))


# Template sets in host/pose/template_file.cpp's layout, default parameters.
def template_set(parts):
    out = b'FSEDGETP' + struct.pack('<i', 1) + struct.pack('<iiifi', 600, 40, 128, 35.0, 400)
    out += struct.pack('<i', len(parts))
    for obj_id, name, views in parts:
        out += struct.pack('<ii', obj_id, len(name)) + name + struct.pack('<fi', 50.0, len(views))
        for rotation, points in views:
            out += struct.pack('<9d', *rotation) + struct.pack('<fi', -10.0, len(points))
            for p in points:
                out += struct.pack('<3f', *p)
            for p in points:
                out += struct.pack('<3f', 0, 0, 1)
    return out


identity = [1, 0, 0, 0, 1, 0, 0, 0, 1]
quarter = [0, -1, 0, 1, 0, 0, 0, 0, 1]
w('template_file/one_part.bin',
  template_set([(1, b'obj_01.stl', [(identity, [(1, 2, 3), (4, 5, 6)]), (quarter, [(0, 0, 0)])])]))
w('template_file/two_parts.bin', template_set([(1, b'obj_01.stl', [(identity, [(1, 2, 3)])]), (7, b'obj_07.stl', [])]))
shutil.rmtree(TMP)
