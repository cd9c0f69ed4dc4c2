#!/usr/bin/env python3
"""Writes the hand-made seed corpora of the fuzz targets into tests/fuzz/corpus/<target>/.

Every seed is small and written from scratch here (no sample data is copied): text inputs as
literals, binary ones (glTF/GLB models, OSM PBF, cached hierarchy and cluster-tree blobs)
encoded by the small writers below. Re-run after changing a format:

    python3 tests/fuzz/make_seeds.py

Seeds that reproduce fixed bugs live next to these as regression-*; this script leaves any file
it does not write alone.
"""

import base64
import json
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
CORPUS = os.path.join(HERE, "corpus")


def put(target, name, data):
    d = os.path.join(CORPUS, target)
    os.makedirs(d, exist_ok=True)
    if isinstance(data, str):
        data = data.encode("utf-8")
    with open(os.path.join(d, name), "wb") as f:
        f.write(data)


def compact(obj):
    return json.dumps(obj, separators=(",", ":"), ensure_ascii=False)


# ----------------------------------------------------------------------------------------------
# Shared small data: a 5-station metro (LOOM), POIs, a 3 x 3 street grid. Vienna coordinates.

STATIONS = [("a", "A", "Alpha", 16.360, 48.200), ("b", "B", "Bravo", 16.370, 48.210),
            ("c", "C", "Charlie", 16.380, 48.200), ("d", "D", "Delta", 16.370, 48.190),
            ("e", "", "", 16.390, 48.212)]  # e: a junction, not a station


def loom(with_junction=True, reversed_geometry=False):
    feats = []
    for nid, sid, label, lon, lat in STATIONS:
        if not with_junction and not sid:
            continue
        props = {"id": nid}
        if sid:
            props["station_id"] = sid
            props["station_label"] = label
        feats.append({"type": "Feature", "geometry": {"type": "Point", "coordinates": [lon, lat]},
                      "properties": props})
    pos = {s[0]: [s[3], s[4]] for s in STATIONS}
    edges = [("a", "b", [{"id": "u1", "label": "U1", "color": "#e3000f"}]),
             ("b", "c", [{"id": "u1", "label": "U1", "color": "e3000f"}, {"id": "u3", "label": "U3"}]),
             ("a", "d", [{"id": "u2", "label": "U2", "color": "a862a4"}]),
             ("d", "c", [{"label": "U2"}])]
    if with_junction:
        edges.append(("b", "e", [{"id": "u1", "label": "U1"}]))
    for f, t, lines in edges:
        coords = [pos[f], [(pos[f][0] + pos[t][0]) / 2, (pos[f][1] + pos[t][1]) / 2 + 0.001], pos[t]]
        if reversed_geometry:
            coords.reverse()
        feats.append({"type": "Feature", "geometry": {"type": "LineString", "coordinates": coords},
                      "properties": {"from": f, "to": t, "lines": lines}})
    return compact({"type": "FeatureCollection", "features": feats})


GRID_NODES = [(i * 3 + j + 1, 48.200 + 0.005 * i, 16.360 + 0.005 * j) for i in range(3) for j in range(3)]
GRID_WAYS = [(101, [1, 2, 3], {"highway": "primary", "name": "South"}),
             (102, [4, 5, 6], {"highway": "residential"}),
             (103, [7, 8, 9], {"highway": "secondary", "name": "North & Co"}),
             (104, [1, 4, 7], {"highway": "tertiary"}),
             (105, [2, 5, 8, 8], {"highway": "footway"}),
             (106, [3, 6, 9, 42], {"highway": "service"}),  # 42: missing node (split)
             (107, [1, 5, 9], {"highway": "construction"}),  # not a road
             (108, [4, 5, 2, 4], {"highway": "pedestrian", "area": "yes"})]


def osm_xml():
    out = ['<?xml version="1.0" encoding="UTF-8"?>', '<osm version="0.6" generator="tourmap-seed">']
    for nid, lat, lon in GRID_NODES:
        out.append(f' <node id="{nid}" lat="{lat:.7f}" lon="{lon:.7f}" version="1"/>')
    for wid, refs, tags in GRID_WAYS:
        body = "".join(f'<nd ref="{r}"/>' for r in refs)
        body += "".join(f'<tag k="{k}" v="{v.replace("&", "&amp;")}"/>' for k, v in tags.items())
        out.append(f' <way id="{wid}" version="1">{body}</way>')
    out.append(' <relation id="1" version="1"><member type="way" ref="101" role=""/><tag k="type" v="route"/></relation>')
    out.append("</osm>")
    return "\n".join(out) + "\n"


def inline_roads():
    coords = {nid: [lon, lat] for nid, lat, lon in GRID_NODES}
    feats = []
    for wid, refs, tags in GRID_WAYS[:6]:
        line = [coords[r] for r in refs if r in coords]
        feats.append({"type": "Feature", "properties": {"highway": tags["highway"], "name": tags.get("name", "")},
                      "geometry": {"type": "LineString", "coordinates": line}})
    feats.append({"type": "Feature", "properties": None, "geometry": {
        "type": "MultiLineString", "coordinates": [[coords[1], coords[5]], [coords[5], coords[9]]]}})
    return {"type": "FeatureCollection", "features": feats}


# ----------------------------------------------------------------------------------------------
# Protobuf / OSM PBF writer (enough for HeaderBlock + PrimitiveBlock with dense nodes and ways).

def varint(v):
    out = bytearray()
    while True:
        b = v & 0x7F
        v >>= 7
        if v:
            out.append(b | 0x80)
        else:
            out.append(b)
            return bytes(out)


def zigzag(v):
    return (v << 1) ^ (v >> 63)


def field_bytes(num, data):
    return varint((num << 3) | 2) + varint(len(data)) + data


def field_varint(num, v):
    return varint(num << 3) + varint(v)


def packed(num, values, signed=False):
    return field_bytes(num, b"".join(varint(zigzag(v) if signed else v) for v in values))


def deltas(values):
    out, prev = [], 0
    for v in values:
        out.append(v - prev)
        prev = v
    return out


def pbf_blob(kind, payload, compress):
    if compress:
        blob = field_varint(2, len(payload)) + field_bytes(3, zlib.compress(payload))
    else:
        blob = field_bytes(1, payload)
    header = field_bytes(1, kind.encode()) + field_varint(3, len(blob))
    return struct.pack(">I", len(header)) + header + blob


def osm_transit_xml():
    """A tram line both ways under a route master, a stop area, a museum node and a gallery way."""
    tag = lambda k, v: f'<tag k="{k}" v="{v}"/>'
    nodes = [(1, 48.200, 16.360, tag("public_transport", "stop_position") + tag("name", "Markt")),
             (2, 48.200, 16.370, tag("public_transport", "stop_position") + tag("name", "Rathaus")),
             (3, 48.2003, 16.3702, tag("public_transport", "platform") + tag("name", "1")),
             (4, 48.200, 16.380, tag("tourism", "museum") + tag("name", "Museum") + tag("wikidata", "Q1")),
             (5, 48.201, 16.381, ""), (6, 48.202, 16.382, ""), (7, 48.201, 16.383, "")]
    out = ['<?xml version="1.0" encoding="UTF-8"?>', '<osm version="0.6" generator="tourmap-seed">']
    for nid, lat, lon, tags in nodes:
        out.append(f' <node id="{nid}" lat="{lat:.7f}" lon="{lon:.7f}" version="1">{tags}</node>')
    out.append(' <way id="20" version="1"><nd ref="5"/><nd ref="6"/><nd ref="7"/><nd ref="5"/>'
               + tag("tourism", "gallery") + tag("name", "Galerie") + '</way>')
    member = lambda t, r, role: f'<member type="{t}" ref="{r}" role="{role}"/>'
    out.append(' <relation id="10" version="1">' + member("node", 1, "stop") + member("node", 2, "stop")
               + member("node", 3, "platform") + tag("type", "route") + tag("route", "tram") + tag("ref", "1") + '</relation>')
    out.append(' <relation id="11" version="1">' + member("node", 2, "stop") + member("node", 1, "stop")
               + tag("type", "route") + tag("route", "tram") + tag("ref", "1") + tag("colour", "#ff0000") + '</relation>')
    out.append(' <relation id="12" version="1">' + member("relation", 10, "") + member("relation", 11, "")
               + tag("type", "route_master") + tag("ref", "1") + '</relation>')
    out.append(' <relation id="13" version="1">' + member("node", 2, "stop") + member("node", 3, "platform")
               + tag("type", "public_transport") + tag("public_transport", "stop_area") + tag("name", "Rathausplatz") + '</relation>')
    out.append("</osm>")
    return "\n".join(out) + "\n"


def osm_pbf(compress):
    header = field_bytes(4, b"OsmSchema-V0.6") + field_bytes(4, b"DenseNodes") + field_bytes(16, b"tourmap-seed")
    strings = [b""]

    def sid(s):
        s = s.encode()
        if s not in strings:
            strings.append(s)
        return strings.index(s)

    ids = [n[0] for n in GRID_NODES]
    lats = [round(n[1] * 1e7) for n in GRID_NODES]
    lons = [round(n[2] * 1e7) for n in GRID_NODES]
    kv = []
    for _ in GRID_NODES:
        kv.append(0)  # no tags
    dense = packed(1, deltas(ids), True) + packed(8, deltas(lats), True) + packed(9, deltas(lons), True) + \
        packed(10, kv)
    ways = b""
    for wid, refs, tags in GRID_WAYS:
        keys = [sid(k) for k in tags]
        vals = [sid(v) for v in tags.values()]
        way = field_varint(1, wid) + packed(2, keys) + packed(3, vals) + packed(8, deltas(refs), True)
        ways += field_bytes(3, way)
    table = b"".join(field_bytes(1, s) for s in strings)
    block = field_bytes(1, table) + field_bytes(2, field_bytes(2, dense)) + field_bytes(2, ways) + \
        field_varint(17, 100)
    return pbf_blob("OSMHeader", header, compress) + pbf_blob("OSMData", block, compress)


# ----------------------------------------------------------------------------------------------
# glTF: a tiny skinned "character" (a triangulated box over two joints, one rotation clip) and a
# static mesh, as .gltf JSON (buffer in a data: URI) and as .glb.

def mat4_identity():
    return [1.0 if i % 5 == 0 else 0.0 for i in range(16)]


def gltf_model(skinned=True, animated=True, with_normals=True, byte_joints=False):
    positions = [(-0.2, 0, -0.1), (0.2, 0, -0.1), (0.2, 0, 0.1), (-0.2, 0, 0.1),
                 (-0.2, 1.7, -0.1), (0.2, 1.7, -0.1), (0.2, 1.7, 0.1), (-0.2, 1.7, 0.1)]
    indices = [0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6,
               3, 0, 4, 3, 4, 7]
    blobs = []  # (bytes, target, accessor dict)

    def add(data, accessor, target=None):
        blobs.append((data, target, accessor))
        return len(blobs) - 1

    lo = [min(p[k] for p in positions) for k in range(3)]
    hi = [max(p[k] for p in positions) for k in range(3)]
    attrs = {"POSITION": add(b"".join(struct.pack("<3f", *p) for p in positions),
                             {"componentType": 5126, "count": 8, "type": "VEC3", "min": lo, "max": hi}, 34962)}
    if with_normals:
        normals = [(0, -1, 0)] * 4 + [(0, 1, 0)] * 4
        attrs["NORMAL"] = add(b"".join(struct.pack("<3f", *n) for n in normals),
                              {"componentType": 5126, "count": 8, "type": "VEC3"}, 34962)
    if skinned:
        joints = [(0, 1, 0, 0)] * 8
        weights = [(1.0, 0, 0, 0)] * 4 + [(0.25, 0.75, 0, 0)] * 4
        if byte_joints:
            jdata = b"".join(struct.pack("<4B", *j) for j in joints)
            jtype = 5121
        else:
            jdata = b"".join(struct.pack("<4H", *j) for j in joints)
            jtype = 5123
        attrs["JOINTS_0"] = add(jdata, {"componentType": jtype, "count": 8, "type": "VEC4"}, 34962)
        attrs["WEIGHTS_0"] = add(b"".join(struct.pack("<4f", *w) for w in weights),
                                 {"componentType": 5126, "count": 8, "type": "VEC4"}, 34962)
    idx = add(b"".join(struct.pack("<H", i) for i in indices),
              {"componentType": 5123, "count": len(indices), "type": "SCALAR"}, 34963)
    doc = {"asset": {"version": "2.0", "generator": "tourmap-seed"}, "scene": 0,
           "meshes": [{"name": "box", "primitives": [{"attributes": attrs, "indices": idx, "mode": 4,
                                                      "material": 0}]}],
           "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.3, 0.2, 1.0]}}]}
    if skinned:
        ibm = mat4_identity() + [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -0.85, 0, 1]
        inv = add(struct.pack("<32f", *ibm), {"componentType": 5126, "count": 2, "type": "MAT4"})
        doc["nodes"] = [{"name": "body", "mesh": 0, "skin": 0},
                        {"name": "hips", "children": [2], "translation": [0, 0, 0]},
                        {"name": "chest", "translation": [0, 0.85, 0], "rotation": [0, 0, 0, 1]}]
        doc["skins"] = [{"joints": [1, 2], "inverseBindMatrices": inv, "skeleton": 1}]
        doc["scenes"] = [{"nodes": [0, 1]}]
        if animated:
            times = add(struct.pack("<3f", 0, 0.5, 1.0),
                        {"componentType": 5126, "count": 3, "type": "SCALAR", "min": [0], "max": [1.0]})
            rots = add(struct.pack("<12f", 0, 0, 0, 1, 0, 0, 0.2588190, 0.9659258, 0, 0, 0, 1),
                       {"componentType": 5126, "count": 3, "type": "VEC4"})
            moves = add(struct.pack("<9f", 0, 0, 0, 0, 0.1, 0, 0, 0, 0),
                        {"componentType": 5126, "count": 3, "type": "VEC3"})
            doc["animations"] = [{"name": "Walk",
                                  "samplers": [{"input": times, "output": rots, "interpolation": "LINEAR"},
                                               {"input": times, "output": moves, "interpolation": "STEP"}],
                                  "channels": [{"sampler": 0, "target": {"node": 2, "path": "rotation"}},
                                               {"sampler": 1, "target": {"node": 1, "path": "translation"}}]}]
    else:
        doc["nodes"] = [{"name": "box", "mesh": 0, "scale": [2, 1, 1]}]
        doc["scenes"] = [{"nodes": [0]}]
    # One buffer, 4-aligned views.
    buf = bytearray()
    views, accessors = [], []
    for data, target, acc in blobs:
        while len(buf) % 4:
            buf.append(0)
        view = {"buffer": 0, "byteOffset": len(buf), "byteLength": len(data)}
        if target:
            view["target"] = target
        views.append(view)
        buf += data
        acc = dict(acc)
        acc["bufferView"] = len(views) - 1
        accessors.append(acc)
    doc["bufferViews"] = views
    doc["accessors"] = accessors
    return doc, bytes(buf)


def gltf_json(doc, buf):
    doc = dict(doc)
    doc["buffers"] = [{"byteLength": len(buf),
                       "uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode()}]
    return json.dumps(doc, indent=1)


def glb(doc, buf):
    doc = dict(doc)
    doc["buffers"] = [{"byteLength": len(buf)}]
    js = compact(doc).encode()
    js += b" " * (-len(js) % 4)
    bin_ = buf + b"\0" * (-len(buf) % 4)
    body = struct.pack("<I4s", len(js), b"JSON") + js + struct.pack("<I4s", len(bin_), b"BIN\0") + bin_
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body


# ----------------------------------------------------------------------------------------------
# Binary caches: crowd hierarchy (core/crowd/hierarchy_io.hpp) and POI cluster tree
# (core/poi/serialize.cpp).

def hierarchy(clusters, indices, root, anims=((30,), (5,))):
    out = b"TMCH" + struct.pack("<IIIi", 1, len(clusters), len(indices), root)
    out += struct.pack("<10d", 2, 3, 2, 3, 0, 1.5, 2.5, 3.5, 7.5, 0)
    for lst in anims:
        out += struct.pack("<I", len(lst)) + b"".join(struct.pack("<Q", v) for v in lst)
    for c in clusters:
        first, count, parent, c0, c1, depth, err, level, lo, hi = c
        out += struct.pack("<IIiiiiff", first, count, parent, c0, c1, depth, err, level)
        out += struct.pack("<6f", *lo, *hi)
    out += b"".join(struct.pack("<I", i) for i in indices)
    return out


def cluster_tree(leaves, inner, root):
    """leaves: [(x, y, worth)]; inner: [(children, level)] in id order after the leaves."""
    nodes, children = [], []
    for i, (x, y, w) in enumerate(leaves):
        nodes.append([x, y, x, y, x, y, w, 1, i, -1, 0, 0, 0])
    for kids, level in inner:
        xs = [nodes[k][0] for k in kids]
        ys = [nodes[k][1] for k in kids]
        best = max(kids, key=lambda k: nodes[k][6])
        nid = len(nodes)
        nodes.append([sum(xs) / len(xs), sum(ys) / len(ys), min(xs), min(ys), max(xs), max(ys), nodes[best][6],
                      sum(nodes[k][7] for k in kids), nodes[best][8], -1, len(children), len(kids), level])
        for k in kids:
            nodes[k][9] = nid
        children += kids
    body = b""
    for n in nodes:
        body += struct.pack("<7d", *n[:7]) + struct.pack("<6I", n[7], n[8], n[9] & 0xFFFFFFFF, n[10], n[11], n[12])
    body += b"".join(struct.pack("<I", c) for c in children)
    head = b"TMCT" + struct.pack("<IQQQI", 1, len(leaves), len(nodes), len(children), root)
    return head + struct.pack("<I", zlib.crc32(body)) + body


# ----------------------------------------------------------------------------------------------

def main():
    # --- metro imports
    put("metro_loom", "five_stations.json", loom())
    put("metro_loom", "reversed_geometry.json", loom(with_junction=False, reversed_geometry=True))
    put("metro_loom", "empty.json", '{"type":"FeatureCollection","features":[]}')
    put("metro_line_csv", "lisbon_like.csv",
        "line_id,seq_on_line,name,lat,lon,line_en,line_local,gtfs_stop_id\n"
        "blue,1,Reboleira,38.7522,-9.2242,Blue,Azul,BR\n"
        "blue,2,Amadora Este,38.7582,-9.2186,Blue,Azul,AE\n"
        "blue,3,Alfornelos,38.7605,-9.2046,Blue,Azul,AF\n"
        "yellow,1,Odivelas,38.7938,-9.1733,Yellow,Amarela,OD\n"
        "yellow,2,Senhor Roubado,38.7857,-9.1722,Yellow,Amarela,SR\n"
        "yellow,3.5,Alfornelos,38.7605,-9.2046,Yellow,Amarela,AF\n")
    put("metro_line_csv", "quoted_colour.csv",
        "\ufeffline,seq,station,latitude,longitude,colour\r\n"
        "\"L1\",1,\"Stop \"\"A\"\"\",48.2,16.3,ff0000\r\n\"L1\",2,\"B, C\",48.21,16.31,NULL\r\n")
    put("metro_station_csvs", "london_like.txt",
        "id,latitude,longitude,name,display_name,zone\n"
        "1,51.5028,-0.2801,Acton Town,Acton<br />Town,3\n"
        "2,51.5143,-0.0755,Aldgate,NULL,1\n"
        "3,51.5154,-0.0726,Aldgate East,\"Aldgate, East\",1\n"
        "\n====\n"
        "line,name,colour,stripe\n1,Bakerloo Line,ab6612,NULL\n2,Central Line,#dc241f,NULL\n"
        "\n====\n"
        "station1,station2,line,time\n1,2,1,4\n2,3,2,2\n3,1,1,1\n")
    # --- GTFS: stops, routes, trips, stop_times, shapes (a parent station, CRLF, a quoted comma,
    # a shape, a rail and a bus route)
    put("metro_gtfs", "liechtenstein_bus_and_rail.txt",
        "stop_id,stop_name,stop_lat,stop_lon,location_type,parent_station\r\n"
        "S1,\"Schaan, Bahnhof\",47.1656,9.5094,1,\r\np1,Schaan 1,47.1657,9.5095,0,S1\r\n"
        "v,Vaduz Post,47.1399,9.5215,,\r\nb,Balzers,47.0667,9.5028,,\r\n"
        "\n====\n"
        "route_id,route_short_name,route_long_name,route_type,route_color\n11,11,,3,E2001A\nR,,Rail,2,\n"
        "\n====\n"
        "route_id,service_id,trip_id,shape_id\n11,d,t1,sh1\n11,d,t2,\nR,d,t3,\n"
        "\n====\n"
        "trip_id,arrival_time,departure_time,stop_id,stop_sequence\n"
        "t1,08:00:00,08:00:00,p1,1\nt1,08:10:00,08:10:00,v,2\nt1,08:25:00,08:25:00,b,3\n"
        "t2,09:00:00,09:00:00,b,1\nt2,09:15:00,09:15:00,v,2\nt3,10:00:00,10:00:00,S1,1\nt3,10:20:00,10:20:00,b,2\n"
        "\n====\n"
        "shape_id,shape_pt_lat,shape_pt_lon,shape_pt_sequence\n"
        "sh1,47.1657,9.5095,1\nsh1,47.15,9.515,2\nsh1,47.1399,9.5215,3\nsh1,47.1,9.51,4\nsh1,47.0667,9.5028,5\n")
    # --- POIs: first byte picks the file name: 0 .csv, 1 .json, 2 .geojson, 3 .js
    put("pois", "csv.txt", "0name,lon,lat,category,rank,popularity,url,id\n"
        "Opera,16.369,48.203,sight,1,0.9,\"https://a.example, https://b.example\",op\n"
        "Museum,16.361,48.204,museum,NULL,,https://m.example,mu\n"
        "\"Caf\u00c3\u00a9 Central\",16.365,48.210,,2,,,\n")
    put("pois", "geojson.txt", "2" + compact({"type": "FeatureCollection", "features": [
        {"type": "Feature", "id": 7, "geometry": {"type": "Point", "coordinates": [16.37, 48.2]},
         "properties": {"NAME": "Stephansdom", "Wikipedia_Type": "church", "rank": "3", "image": "x.jpg"}},
        {"type": "Feature", "geometry": {"type": "Point", "coordinates": [16.36, 48.21, 170]},
         "properties": {"title": "Shakespeare\u00e2\u20ac\u2122s", "popularity": 0.5, "objectid": 12.0}}]}))
    put("pois", "js_array.txt", "3var sights = " + compact([
        {"name": "Prater", "lng": "16.40", "lat": 48.21, "type": "park", "website": "https://p.example"},
        {"title": "Belvedere", "longitude": 16.38, "latitude": "48.19", "wikidata": "Q303139", "id": "b"}]) + ";\n")
    put("pois", "json_array.txt", "1" + compact([{"name": "Albertina", "lon": 16.368, "lat": 48.204}]))
    # --- CSV and text repair
    put("csv", "quoted.csv", "\ufeffid,name,lon,lat\r\n1,\"Quote \"\"q\"\"\",16.3,48.2\r\n2,\"multi\nline, comma\",1e2,-0.5\r\n\r\n")
    put("csv", "nulls.csv", "a,b,c\nNULL,,null\n \" x\",y,z\n")
    put("text_repair", "mojibake.txt", "Shakespeare\u00e2\u20ac\u2122s Globe \u2013 Caf\u00c3\u00a9")
    put("text_repair", "clean.txt", "Stephansdom, Wien \u00e9\u00e8 \U0001f600")
    put("text_repair", "latin1.bin", b"Caf\xe9 \xc3\xa9\xc2")
    # --- OSM
    put("osm_xml", "grid.osm", osm_xml())
    put("osm_xml", "transit.osm", osm_transit_xml())
    put("osm_pbf", "grid_zlib.osm.pbf", osm_pbf(compress=True))
    put("osm_pbf", "grid_raw.osm.pbf", osm_pbf(compress=False))
    # --- manifest
    put("manifest", "sample.json", compact({
        "cities": [{"id": "vienna", "name": "Vienna",
                    "metro": {"format": "loom", "files": ["metro/loom_wien.json"], "attribution": "x"},
                    "pois": {"file": "poi/v.json", "category": "sight", "attribution": "y"}},
                   {"id": "london", "name": "London", "metro": {"format": "station-csvs",
                    "files": ["/abs/s.csv", "l.csv", "c.csv"]}}],
        "roads": [{"id": "monaco", "name": "Monaco", "file": "roads/monaco.osm.gz", "attribution": "OSM"}]}))
    # --- request bodies and parameters
    roads = inline_roads()
    put("roads_in", "grid.json", compact(roads))
    put("deform_request", "focus_circle.json", "0" + compact({
        "roads": "grid", "grid": {"kind": "adaptive", "base": 8, "depth": 2, "c": 2},
        "regions": [{"center": [16.365, 48.205], "radius_m": 300, "scale": 2.5}],
        "weights": {"road": 1, "quad": 0.5, "smooth": 0.1}, "boundary": "sliding", "output": {"roads": "positions"}}))
    put("deform_request", "focus_polygon_inline.json", "0" + compact({
        "roads": roads, "grid": {"kind": "uniform", "n": 12}, "solver": "cg", "cg": {"max_iterations": 500,
        "tolerance": 1e-6}, "regions": [{"polygon": [[16.36, 48.2], [16.37, 48.2], [16.37, 48.21], [16.36, 48.2]],
                                         "scale": 0.5}], "map_points": [[16.365, 48.205]], "relax": True}))
    put("deform_request", "mental.json", "1" + compact({
        "roads": "grid", "grid": {"kind": "edges"}, "guides": [{"vertex": 5, "target": [16.366, 48.206]},
        {"point": [16.361, 48.2], "target": [16.359, 48.199]}], "check_crossings": True, "time_limit_ms": 500}))
    put("deform_request", "destination.json", "2" + compact({
        "roads": "grid", "route": [1, 2, 3, 6], "sketch": [[16.36, 48.2], [16.372, 48.202], [16.37, 48.205]],
        "simplify_m": 5, "output": {"roads": "none", "grid": False}}))
    put("geojson_in", "polygon.json", compact({"type": "Polygon", "coordinates": [
        [[16.35, 48.19], [16.39, 48.19], [16.39, 48.22], [16.35, 48.22], [16.35, 48.19]],
        [[16.36, 48.20], [16.37, 48.20], [16.37, 48.21], [16.36, 48.20]]]}))
    put("geojson_in", "feature_multipolygon.json", compact({"type": "Feature", "properties": {}, "geometry": {
        "type": "MultiPolygon", "coordinates": [[[[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]]],
                                                [[[2, 2], [3, 2], [2.5, 3], [2, 2]]]]}}))
    put("geojson_in", "query_body.json", compact({"bbox": [16.3, 48.1, 16.4, 48.3], "within": {
        "type": "Polygon", "coordinates": [[[16.3, 48.1], [16.4, 48.1], [16.4, 48.3], [16.3, 48.1]]]}}))
    put("geojson_in", "position.json", "[16.37, 48.2, 171.5]")
    put("url_params", "pois.txt", "/api/v1/cities/vienna/pois?bbox=16.3%2C48.1,16.4,48.3&limit=10&offset=0&geometry=true")
    put("url_params", "layout.txt", "/api/v1/cities/x-y_z/layout?lengths=uniform&solver=fast&rank=proxy&time_limit_s=0.5&w_r=1&w_rho=0.5&k=500&l_const=12#frag")
    put("url_params", "escapes.txt", "/a%20b/c+d?q=%C3%A9+x&&empty=&flag&width=64&height=1e3")
    put("crowd_view", "views.txt", "\n".join(compact(m) for m in [
        {"type": "view", "scene": "office", "mode": "vdr+oc", "poe": 0.5, "width": 640, "height": 360,
         "quality": 70, "heatmap": False, "animate": True, "count": 50},
        {"type": "view", "camera": {"eye": [10, 20, 30], "target": [0, 0, 0], "fov": 45}},
        {"type": "view", "scene": "stampede", "mode": "nolod"},
        {"type": "view", "mode": "vdr", "camera": {"eye": [0, 50, 0], "target": [0, 0, 0]}}]))
    put("crowd_view", "bad.txt", '{"type":"view"}\n{"type":"view","scene":"exhibition","width":"wide"}\n[1]\n')
    put("ws_messages", "crowd.txt", "0" + "\n".join(compact(m) for m in [
        {"type": "view", "scene": "office", "width": 320, "height": 240},
        {"type": "ack", "frame": 0}, {"type": "ack", "frame": 5}, {"type": "ack"},
        {"type": "view", "camera": {"eye": [5, 5, 5], "target": [0, 1, 0]}}, "not json"]))
    put("ws_messages", "events.txt", "1" + '{"type":"ping"}\n{"type":"pong"}\n{}\nnull')
    # --- whole requests: "METHOD TARGET", headers, empty line, body
    def req(method, target, body="", ctype="application/json", extra=""):
        return f"{method} {target}\nContent-Type: {ctype}\n{extra}\n{body}"
    put("handlers", "cities.txt", req("GET", "/api/v1/cities", extra="Accept-Encoding: gzip\n"))
    put("handlers", "city.txt", req("HEAD", "/api/v1/cities/fuzzville", extra='If-None-Match: W/"0", *\n'))
    put("handlers", "metro.txt", req("GET", "/api/v1/cities/fuzzville/metro?bbox=16.3,48.1,16.4,48.3"))
    put("handlers", "pois.txt", req("GET", "/api/v1/cities/fuzzville/pois?limit=2&offset=1"))
    put("handlers", "pois_query.txt", req("POST", "/api/v1/cities/fuzzville/pois/query", compact({
        "within": {"type": "Polygon", "coordinates": [[[16.35, 48.19], [16.39, 48.19], [16.39, 48.22], [16.35, 48.19]]]},
        "categories": ["sight"], "limit": 5})))
    put("handlers", "layout_get.txt", req("GET", "/api/v1/cities/fuzzville/layout?solver=fast&time_limit_s=1"))
    put("handlers", "layout_post.txt", req("POST", "/api/v1/cities/fuzzville/layout", compact(
        {"lengths": "uniform", "solver": "auto", "rank": "uniform", "time_limit_s": 1, "l_const": 20})))
    put("handlers", "map_svg.txt", req("GET", "/api/v1/cities/fuzzville/map.svg?width=400&height=300&solver=fast&time_limit_s=1"))
    put("handlers", "map_png.txt", req("GET", "/api/v1/cities/fuzzville/map.png?paper=a4&orientation=portrait&dpi=72&solver=fast&time_limit_s=1"))
    put("handlers", "visual_worth.txt", req("GET", "/api/v1/cities/fuzzville/visual-worth?width=16&height=8&k=300"))
    put("handlers", "clusters_geo.txt", req("GET", "/api/v1/cities/fuzzville/clusters?m=3"))
    put("handlers", "clusters_layout.txt", req("GET", "/api/v1/cities/fuzzville/clusters?space=layout&bbox=-1000,-1000,1000,1000&m=2&solver=fast&time_limit_s=1"))
    put("handlers", "roads.txt", req("GET", "/api/v1/roads"))
    put("handlers", "road.txt", req("GET", "/api/v1/roads/grid?bbox=16.36,48.2,16.365,48.205", extra="Accept-Encoding: gzip, br\n"))
    put("handlers", "deform_focus.txt", req("POST", "/api/v1/deform/focus", compact({
        "roads": "grid", "grid": {"kind": "adaptive", "base": 6, "depth": 2},
        "regions": [{"center": [16.365, 48.205], "radius_m": 250, "scale": 3}]})))
    put("handlers", "deform_focus_binary.txt", req("POST", "/api/v1/deform/focus", compact({
        "roads": "grid", "regions": [{"center": [16.365, 48.205], "radius_m": 250, "scale": 3}],
        "output": {"roads": "positions", "grid": False}}),
        extra="Accept: application/json;q=0.5, application/octet-stream\n"))
    put("handlers", "deform_mental.txt", req("POST", "/api/v1/deform/mental", compact({
        "roads": roads, "grid": {"kind": "edges"}, "guides": [{"vertex": 4, "target": [16.366, 48.206]}]})))
    put("handlers", "deform_destination.txt", req("POST", "/api/v1/deform/destination", compact({
        "roads": "grid", "grid": {"kind": "uniform", "n": 8}, "route": [1, 2, 3],
        "sketch": [[16.36, 48.2], [16.37, 48.201]], "relax": True, "check_crossings": True}),
        ctype="application/geo+json; charset=utf-8"))
    put("handlers", "crowd_scenes.txt", req("GET", "/api/v1/crowd/scenes"))
    put("handlers", "system.txt", req("GET", "/healthz"))
    put("handlers", "api_index.txt", req("GET", "/api/v1"))
    put("handlers", "metrics.txt", req("GET", "/metrics"))
    put("handlers", "openapi.txt", req("GET", "/api/v1/openapi.yaml"))
    put("handlers", "static.txt", req("GET", "/assets/app-1234.js"))
    put("handlers", "static_traversal.txt", req("GET", "/assets/%2e%2e/..%2fsecret.txt"))
    put("handlers", "method.txt", req("DELETE", "/api/v1/cities"))
    # --- raw HTTP bytes into a connection (http_raw): framing, chunking, trailers, pipelining
    crlf = "\r\n"
    put("http_raw", "get.txt", "GET /healthz HTTP/1.1" + crlf + "Host: x" + crlf + crlf)
    put("http_raw", "pipelined.txt", ("GET /api/v1/cities HTTP/1.1" + crlf + "Host: x" + crlf + crlf) +
        ("HEAD /api/v1/roads HTTP/1.1" + crlf + "Host: x" + crlf + "Accept-Encoding: gzip" + crlf + crlf) +
        ("GET /metrics HTTP/1.0" + crlf + crlf))
    body = compact({"within": {"type": "Polygon", "coordinates": [[[16.3, 48.1], [16.4, 48.1], [16.4, 48.3], [16.3, 48.1]]]}})
    put("http_raw", "post_length.txt", "POST /api/v1/cities/fuzzville/pois/query HTTP/1.1" + crlf + "Host: x" + crlf +
        "Content-Type: application/json" + crlf + "Content-Length: " + str(len(body)) + crlf + crlf + body)
    put("http_raw", "post_chunked_trailer.txt", "POST /api/v1/cities/fuzzville/pois/query HTTP/1.1" + crlf +
        "Host: x" + crlf + "Content-Type: application/json" + crlf + "Transfer-Encoding: chunked" + crlf + crlf +
        "%x" % 10 + ";ext=1" + crlf + body[:10] + crlf + "%x" % (len(body) - 10) + crlf + body[10:] + crlf +
        "0" + crlf + "X-Checksum: 1" + crlf + "Origin: https://example.org" + crlf + crlf)
    put("http_raw", "expect_continue.txt", "PUT /api/v1/roads/x HTTP/1.1" + crlf + "Host: x" + crlf +
        "Expect: 100-continue" + crlf + "Content-Length: 4" + crlf + crlf + "<osm")
    put("http_raw", "deform.txt", "POST /api/v1/deform/focus HTTP/1.1" + crlf + "Host: x" + crlf +
        "Content-Type: application/json" + crlf + "Connection: close" + crlf + crlf + compact({
            "roads": "grid", "grid": {"kind": "adaptive", "base": 4, "depth": 2},
            "regions": [{"center": [16.362, 48.202], "radius_m": 200, "scale": 2}], "output": {"roads": "none"}}))
    put("http_raw", "websocket.txt", "GET /api/v1/events HTTP/1.1" + crlf + "Host: x" + crlf + "Upgrade: websocket" +
        crlf + "Connection: Upgrade" + crlf + "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==" + crlf +
        "Sec-WebSocket-Version: 13" + crlf + crlf)
    put("http_raw", "unknown_method.txt", "FROBNICATE /api/v1/cities HTTP/1.1" + crlf + "Host: x" + crlf + crlf)
    put("http_raw", "bad_chunk.txt", "POST /api/v1/deform/focus HTTP/1.1" + crlf + "Transfer-Encoding: chunked" +
        crlf + crlf + "zz" + crlf + "abc" + crlf)
    # --- crowd models and caches
    for name, kw in [("skinned", {}), ("static", {"skinned": False}), ("rest_pose", {"animated": False}),
                     ("byte_joints_no_normals", {"byte_joints": True, "with_normals": False})]:
        doc, buf = gltf_model(**kw)
        put("gltf_json", name + ".gltf", gltf_json(doc, buf))
        put("gltf_glb", name + ".glb", glb(doc, buf))
    box = ((0, 0, 0), (1, 1, 1))
    put("hierarchy_io", "three_clusters.bin", hierarchy(
        [(0, 3, -1, 1, 2, 0, 0.5, 0.2, *box), (3, 3, 0, -1, -1, 1, 0, 0.1, *box), (6, 3, 0, -1, -1, 1, 0, 0, *box)],
        [0, 1, 2, 0, 2, 3, 4, 5, 6], 0))
    put("hierarchy_io", "empty.bin", hierarchy([], [], -1, anims=((), ())))
    put("poi_tree", "three_leaves.bin", cluster_tree([(0, 0, 1), (10, 0, 2), (0, 10, 0.5)], [([0, 1, 2], 1)], 3))
    put("poi_tree", "binary.bin", cluster_tree([(0, 0, 1), (1, 0, 2), (5, 5, 3), (6, 5, 0)],
                                               [([0, 1], 1), ([2, 3], 1), ([4, 5], 2)], 6))
    put("poi_tree", "empty.bin", cluster_tree([], [], 0))


if __name__ == "__main__":
    main()
