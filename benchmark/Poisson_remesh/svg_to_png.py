#!/usr/bin/env python3
# svg_to_png.py IN.svg OUT.png -- rasterizes the density maps that write_density_map_svg() draws
# (filled triangles and the colour bar; no text) into a PNG with the standard library only, for
# RESULTS.md pictures on machines without an SVG renderer. Not a general SVG renderer.
import re, sys, zlib, struct
svg = open(sys.argv[1]).read()
W = int(float(re.search(r'width="([\d.]+)"', svg).group(1))); H = int(float(re.search(r'height="([\d.]+)"', svg).group(1)))
img = [[(255,255,255)]*W for _ in range(H)]
for m in re.finditer(r'<path d="M([\d.]+) ([\d.]+)L([\d.]+) ([\d.]+)L([\d.]+) ([\d.]+)Z" fill="#(\w{6})"', svg):
    x0,y0,x1,y1,x2,y2 = map(float, m.groups()[:6]); c = m.group(7); col = (int(c[0:2],16), int(c[2:4],16), int(c[4:6],16))
    ymin = max(0,int(min(y0,y1,y2))); ymax = min(H-1,int(max(y0,y1,y2))+1)
    xmin = max(0,int(min(x0,x1,x2))); xmax = min(W-1,int(max(x0,x1,x2))+1)
    d = (x1-x0)*(y2-y0)-(x2-x0)*(y1-y0)
    if d == 0: continue
    for y in range(ymin, ymax+1):
        for x in range(xmin, xmax+1):
            px, py = x+0.5, y+0.5
            a = ((x1-px)*(y2-py)-(x2-px)*(y1-py))/d; b = ((x2-px)*(y0-py)-(x0-px)*(y2-py))/d
            if a >= -0.02 and b >= -0.02 and 1-a-b >= -0.02: img[y][x] = col
for m in re.finditer(r'<rect x="([\d.]+)" y="([\d.]+)" width="14" height="([\d.]+)" fill="#(\w{6})"', svg):
    x,y,h = float(m.group(1)), float(m.group(2)), float(m.group(3)); c=m.group(4); col=(int(c[0:2],16), int(c[2:4],16), int(c[4:6],16))
    for yy in range(int(y), min(H,int(y+h))):
        for xx in range(int(x), min(W,int(x+14))): img[yy][xx] = col
raw = b''.join(b'\x00' + bytes([v for p in row for v in p]) for row in img)
def chunk(t, d): return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t+d) & 0xffffffff)
open(sys.argv[2],'wb').write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', W, H, 8, 2, 0, 0, 0)) + chunk(b'IDAT', zlib.compress(raw, 9)) + chunk(b'IEND', b''))
