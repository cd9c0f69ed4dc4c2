"""Advance widths of a TrueType font's glyphs, in thousandths of an em, as the rows of
core/metro/label_font.cpp's table (hmtx and the Windows Unicode cmap, format 4; Python's
standard library only):

    python3 scripts/tools/font_widths.py /usr/share/fonts/truetype/dejavu/DejaVuSansCondensed-Bold.ttf
"""
import struct, sys
def tables(data):
    num = struct.unpack('>H', data[4:6])[0]
    out = {}
    for i in range(num):
        tag, _, off, length = struct.unpack('>4sIII', data[12 + 16*i: 28 + 16*i])
        out[tag.decode()] = (off, length)
    return out
def widths(path, codepoints):
    data = open(path, 'rb').read()
    t = tables(data)
    upem = struct.unpack('>H', data[t['head'][0]+18: t['head'][0]+20])[0]
    nhm = struct.unpack('>H', data[t['hhea'][0]+34: t['hhea'][0]+36])[0]
    hmtx = t['hmtx'][0]
    adv = [struct.unpack('>H', data[hmtx+4*i: hmtx+4*i+2])[0] for i in range(nhm)]
    cmap = t['cmap'][0]
    n = struct.unpack('>H', data[cmap+2:cmap+4])[0]
    sub = None
    for i in range(n):
        pid, eid, off = struct.unpack('>HHI', data[cmap+4+8*i: cmap+12+8*i])
        if pid == 3 and eid == 1: sub = cmap + off
    fmt = struct.unpack('>H', data[sub:sub+2])[0]
    assert fmt == 4
    segx2 = struct.unpack('>H', data[sub+6:sub+8])[0]; seg = segx2 // 2
    ends = struct.unpack('>%dH' % seg, data[sub+14: sub+14+segx2])
    starts = struct.unpack('>%dH' % seg, data[sub+16+segx2: sub+16+2*segx2])
    deltas = struct.unpack('>%dh' % seg, data[sub+16+2*segx2: sub+16+3*segx2])
    roff_pos = sub+16+3*segx2
    roffs = struct.unpack('>%dH' % seg, data[roff_pos: roff_pos+segx2])
    def glyph(c):
        for i in range(seg):
            if starts[i] <= c <= ends[i]:
                if roffs[i] == 0: return (c + deltas[i]) & 0xFFFF
                addr = roff_pos + 2*i + roffs[i] + 2*(c - starts[i])
                g = struct.unpack('>H', data[addr:addr+2])[0]
                return (g + deltas[i]) & 0xFFFF if g else 0
        return 0
    res = {}
    for c in codepoints:
        g = glyph(c)
        if g == 0: continue
        res[c] = adv[min(g, nhm-1)] / upem
    return res
if __name__ == '__main__':
    cps = list(range(0x20, 0x7f)) + list(range(0xa0, 0x250)) + list(range(0x2010, 0x2027)) + [0x2032, 0x2033]
    rows = sorted((c, round(v * 1000)) for c, v in widths(sys.argv[1], cps).items())
    for i in range(0, len(rows), 8):
        print('    ' + ' '.join('{0x%04X, %d},' % r for r in rows[i:i + 8]))
