#!/usr/bin/env python3
"""Writes the fuzz targets' seed files, native/fuzz/seeds/<target>/: small centerlines of the project's
own in every variant each reader takes. Run it again after changing it; the files are committed."""
import base64
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))

# A Y: a trunk 0-1, two branches 1-2 and 1-3 (2 poly-lines: 0-1-2 and 1-3).
POINTS = [(0, 0, 0), (0, 0, 10), (6, 0, 18), (-6, 0, 18)]
RADII = [2.0, 1.8, 1.0, 1.2]
LINES = [[0, 1, 2], [1, 3]]


def write(target, name, data):
    folder = os.path.join(HERE, "seeds", target)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def swc():
    write("swc", "y.swc", "# id type x y z radius parent\n1 1 0 0 0 2 -1\n2 3 0 0 10 1.8 1\n"
          "3 3 6 0 18 1.0 2\n4 3 -6 0 18 1.2 2\n")
    write("swc", "crlf_bom_extra_columns.swc",
          "\ufeff# CRLF, a BOM, tabs, an eighth column, two roots\r\n1\t1\t0.0\t0.0\t0.0\t1.5\t-1\t0\r\n"
          "2 3 1e1 0 0 1.25 1 7\r\n\r\n10 3 0 5 0 0.5 -1\r\n11 3 0 5 3.5e0 +0.5 10\r\n")
    write("swc", "unordered_ids.swc", "5 3 0 0 4 1 4\n4 3 0 0 2 1 2\n2 1 0 0 0 1 -1\n6 3 0 3 6 0.7 5\n"
          "7 3 0 -3 6 0.7 5\n8 3 0 -3 9 0.7 7\n")


def vtk():
    pts = "\n".join(" ".join(str(c) for c in p) for p in POINTS)
    cells = sum(len(l) + 1 for l in LINES)
    legacy = "\n".join(f"{len(l)} " + " ".join(map(str, l)) for l in LINES)
    radii = " ".join(map(str, RADII))
    write("vtk", "ascii30_point_scalars.vtk",
          f"# vtk DataFile Version 3.0\nY\nASCII\nDATASET POLYDATA\nPOINTS 4 float\n{pts}\n"
          f"LINES 2 {cells}\n{legacy}\nPOINT_DATA 4\nSCALARS Radius double 1\nLOOKUP_TABLE default\n{radii}\n"
          "VECTORS dir float\n0 0 1 0 0 1 1 0 1 -1 0 1\n")
    write("vtk", "ascii42_cell_field.vtk",
          f"# vtk DataFile Version 4.2\nY, radius per line\nASCII\nDATASET POLYDATA\nPOINTS 4 double\n{pts}\n"
          f"VERTICES 1 2\n1 0\nLINES 2 {cells}\n{legacy}\nCELL_DATA 3\nFIELD FieldData 2\n"
          "id 1 3 int\n0 1 2\ndiameter 1 3 float\n4 3 2.4\nPOINT_DATA 4\n"
          "COLOR_SCALARS rgb 3\n1 0 0 0 1 0 0 0 1 1 1 1\nLOOKUP_TABLE my_table 1\n0 0 0 1\n")
    offsets = [0]
    for l in LINES:
        offsets.append(offsets[-1] + len(l))
    conn = [i for l in LINES for i in l]
    write("vtk", "ascii51_offsets_connectivity.vtk",
          f"# vtk DataFile Version 5.1\nY\nASCII\nDATASET POLYDATA\nPOINTS 4 float\n{pts}\nMETADATA\n"
          f"INFORMATION 0\n\nLINES {len(offsets)} {len(conn)}\nOFFSETS vtktypeint64\n"
          f"{' '.join(map(str, offsets))}\nCONNECTIVITY vtktypeint64\n{' '.join(map(str, conn))}\n"
          f"POINT_DATA 4\nSCALARS radius float\nLOOKUP_TABLE default\n{radii}\n")
    # BINARY: big-endian values right after the line that announces them.
    b = b"# vtk DataFile Version 3.0\nY binary\nBINARY\nDATASET POLYDATA\nPOINTS 4 float\n"
    b += b"".join(struct.pack(">3f", *p) for p in POINTS)
    b += f"\nLINES 2 {cells}\n".encode()
    b += b"".join(struct.pack(f">{len(l) + 1}i", len(l), *l) for l in LINES)
    b += b"\nCELL_DATA 2\nFIELD FieldData 1\nRadius 1 2 double\n" + struct.pack(">2d", 1.5, 1.1)
    b += b"\n"
    write("vtk", "binary30_cell_field.vtk", b)
    u = b"# vtk DataFile Version 5.1\nY grid\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
    u += b"".join(struct.pack(">3d", *p) for p in POINTS)
    u += f"\nCELLS {len(offsets) + 1} {len(conn) + 1}\nOFFSETS vtktypeint64\n".encode()
    u += struct.pack(f">{len(offsets) + 1}q", *offsets, offsets[-1] + 1)
    u += b"\nCONNECTIVITY vtktypeint64\n" + struct.pack(f">{len(conn) + 1}q", *conn, 0)
    u += b"\nCELL_TYPES 3\n" + struct.pack(">3i", 4, 3, 1)
    u += b"\nPOINT_DATA 4\nSCALARS radius float 1\nLOOKUP_TABLE default\n" + struct.pack(">4f", *RADII) + b"\n"
    write("vtk", "binary51_unstructured_grid.vtk", u)


def vtp():
    conn = [i for l in LINES for i in l]
    offsets = []
    for l in LINES:
        offsets.append((offsets[-1] if offsets else 0) + len(l))
    arrays = [  # (section, type, name, components, struct code, values)
        ("PointData", "Float64", "Radius", 1, "d", RADII),
        ("Points", "Float32", "Points", 3, "f", [c for p in POINTS for c in p]),
        ("Lines", "Int64", "connectivity", 1, "q", conn),
        ("Lines", "Int64", "offsets", 1, "q", offsets),
    ]

    def blocks(data, word, big, block_size):
        chunks = [data[i:i + block_size] for i in range(0, len(data), block_size)] or [b""]
        packed = [zlib.compress(c) for c in chunks]
        w = (">" if big else "<") + ("Q" if word == 8 else "I")
        last = len(data) % block_size
        head = b"".join(struct.pack(w, v) for v in [len(chunks), block_size, last] + [len(p) for p in packed])
        return head, b"".join(packed)

    def file(fmt, zlib_on=False, raw=False, word=4, big=False, block_size=32768):
        order = ">" if big else "<"
        w = order + ("Q" if word == 8 else "I")
        appended = b""
        sections = {}
        for section, typ, name, comps, code, values in arrays:
            data = struct.pack(order + f"{len(values)}{code}", *values)
            attrs = f'type="{typ}" Name="{name}" NumberOfComponents="{comps}" format="{fmt}"'
            if zlib_on:
                head, body = blocks(data, word, big, block_size)
            if fmt == "ascii":
                text = " ".join(repr(v) for v in values)
                el = f"<DataArray {attrs}>{text}</DataArray>"
            elif fmt == "binary":
                if zlib_on:
                    enc = base64.b64encode(head) + base64.b64encode(body)
                else:
                    enc = base64.b64encode(struct.pack(w, len(data)) + data)
                el = f"<DataArray {attrs}>\n{enc.decode()}\n</DataArray>"
            else:
                el = f'<DataArray {attrs} offset="{len(appended)}"/>'
                if zlib_on:
                    appended += (head + body) if raw else base64.b64encode(head) + base64.b64encode(body)
                else:
                    stored = struct.pack(w, len(data)) + data
                    appended += stored if raw else base64.b64encode(stored)
            sections.setdefault(section, []).append(el)
        header = (f'<?xml version="1.0"?>\n<VTKFile type="PolyData" version="1.0" '
                  f'byte_order="{"BigEndian" if big else "LittleEndian"}" '
                  f'header_type="{"UInt64" if word == 8 else "UInt32"}"'
                  + (' compressor="vtkZLibDataCompressor"' if zlib_on else "") + ">\n<PolyData>\n"
                  f'<Piece NumberOfPoints="4" NumberOfVerts="0" NumberOfLines="2" NumberOfStrips="0" '
                  f'NumberOfPolys="0">\n')
        body = ""
        for section in ["PointData", "CellData", "Points", "Verts", "Lines", "Strips", "Polys"]:
            body += f"<{section}>\n" + "\n".join(sections.get(section, [])) + f"\n</{section}>\n"
        out = (header + body + "</Piece>\n</PolyData>\n").encode()
        if fmt == "appended":
            out += (f'<AppendedData encoding="{"raw" if raw else "base64"}">\n_').encode() + appended
            out += b"\n</AppendedData>\n"
        return out + b"</VTKFile>\n"

    write("vtp", "ascii.vtp", file("ascii"))
    write("vtp", "binary_base64.vtp", file("binary"))
    write("vtp", "binary_zlib.vtp", file("binary", zlib_on=True))
    write("vtp", "binary_zlib_uint64_bigendian.vtp", file("binary", zlib_on=True, word=8, big=True))
    write("vtp", "appended_raw_zlib_blocks.vtp", file("appended", zlib_on=True, raw=True, block_size=16))
    write("vtp", "appended_base64.vtp", file("appended"))
    write("vtp", "appended_raw_uint64.vtp", file("appended", raw=True, word=8))


def csv():
    # vertices table, a NUL byte, edges table (fuzz_csv splits there).
    write("csv", "vesselgraph_semicolon.csv",
          "id;pos_x;pos_y;pos_z\n0;0;0;0\n1;0;0;10\n2;6;0;18\n3;-6;0;18\n\0"
          "id;node1id;node2id;avgRadiusAvg\n0;0;1;2.0\n1;1;2;1.0\n2;1;3;1.2\n")
    write("csv", "comma_vertex_radius.csv",
          '"x","y","z","radius"\r\n0,0,0,2\r\n0,0,10,1.8\r\n6,0,18,1.0\r\n-6,0,18,1.2\r\n\0'
          "source,target\n0,1\n1,2\n1,3\n2,3\n")
    write("csv", "ids_diameter.csv", "ID,X,Y,Z\n10,0,0,0\n20,1.0,0,0\n30,2.0,1.0,0\n\0"
          "from,to,diameter\n10,20,0.5\n20,30,0.4\n")


def pipeline():
    def value_grid(v):  # coordinates on the grid (s - 96) / 16
        return bytes([round(v * 16) + 96])

    def radius_grid(r):  # radii (s + 8) / 32
        return bytes([round(r * 32) - 8])

    # Structured mode: the Y, radius per point, levels 1, separate, flat caps, fit onto, curvature.
    y = bytes([0b01000010, len(POINTS) - 2, 0])
    for p, r in zip(POINTS, RADII):
        y += b"".join(value_grid(c / 4) for c in p) + radius_grid(r / 2)
    y += bytes([0, 1, 1])  # parents of points 1, 2, 3
    write("pipeline", "y_level1.bin", y)
    # A ring with a chord and a tail, radius per edge, open caps, no fit, level 0.
    ring = bytes([0b00101000, 3, 0b0000101])
    for p in [(0, 0, 0), (4, 0, 0), (4, 4, 0), (0, 4, 0), (-3, 0, 0)]:
        ring += b"".join(value_grid(c) for c in p)
    ring += bytes([0, 1, 2, 0]) + bytes([3, 0, 1, 3])  # tree edges, then 3-0 (the ring) and 1-3 (a chord)
    ring += b"".join(radius_grid(r) for r in [0.5, 0.5, 0.4, 0.4, 0.6, 0.25])
    write("pipeline", "ring_tail_edge_radius.bin", ring)
    # Values from the table of extremes: radius 1 at one end of an edge 2 long, 1e-3 (selector 0xE6)
    # at the other, and a point 1e-3 off its end with radius 0.5 (0xE0). (The seeds must run clean:
    # extremes that break the pipeline today are one mutation away.)
    ext = bytes([0b00000010, 1, 0]) + bytes([96, 96, 96, 24]) + bytes([128, 96, 96, 0xE6])
    ext += bytes([128, 0xE6, 96, 0xE0]) + bytes([0, 1])
    write("pipeline", "extreme_values.bin", ext)
    raw = bytes([0b00000000, 0, 0]) + bytes([96, 96, 96, 24, 0xF0]) + struct.pack("<d", 1e-3)
    raw += bytes([96, 96, 24, 0xFC, 0])
    write("pipeline", "raw_double_near_coincident.bin", raw)
    # SWC mode.
    write("pipeline", "swc_y.bin", b"\x03" + b"1 1 0 0 0 2 -1\n2 3 0 0 10 1.8 1\n3 3 6 0 18 1 2\n4 3 -6 0 18 1.2 2\n")


if __name__ == "__main__":
    swc()
    vtk()
    vtp()
    csv()
    pipeline()
