"""Values of the files a run writes, whatever their format, for compareStates.

    readFoamFile(path)   an OpenFOAM field or list file (<time>/spem/points,
                         particleRho, ...) in ascii or binary: its class and
                         its numbers, flattened (None if it is not a list)
    readVtkArrays(path)  a VTK XML piece (.vtu, .vtp) in any format VTK's
                         writers give it as spemFoam asks (ascii, binary
                         appended raw: uncompressed, zlib or lz4): {section/name:
                         values}, section Points, Cells, PointData,
                         CellData, FieldData, Verts

Only the Python standard library: no numpy, no VTK module on this machine.
"""
import gzip
import re
import struct
import zlib

# ---------------------------------------------------------------- OpenFOAM

_COMPONENTS = {"scalarField": 1, "vectorField": 3, "labelList": 1,
               "scalarList": 1, "vectorList": 3, "symmTensorField": 6,
               "tensorField": 9}


def _readBytes(path):
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rb") as f:
        return f.read()


def readFoamFile(path):
    """(class, [numbers]) of an OpenFOAM list file; None if not a list."""
    data = _readBytes(path)
    start = data.find(b"FoamFile")
    if start < 0:
        return None
    end = data.find(b"}", start)
    header = data[start:end].decode("latin-1")

    def entry(key, default=""):
        m = re.search(r"\b%s\s+\"?([^;\"]*)\"?\s*;" % key, header)
        return m.group(1).strip() if m else default

    cls = entry("class")
    if cls not in _COMPONENTS:
        return None
    binary = entry("format") == "binary"
    arch = entry("arch", "LSB;label=32;scalar=64")
    labelBytes = 8 if "label=64" in arch else 4
    scalarBytes = 4 if "scalar=32" in arch else 8
    nComponents = _COMPONENTS[cls]

    # Skip blanks and // comments up to the count
    i = end + 1
    while True:
        while i < len(data) and data[i:i + 1].isspace():
            i += 1
        if data[i:i + 2] == b"//":
            i = data.find(b"\n", i)
            continue
        break
    m = re.match(rb"(\d+)\s*", data[i:i + 40])
    if not m:
        raise ValueError("%s: no list count" % path)
    n = int(m.group(1))
    i += m.end()
    if n == 0:
        return cls, []
    opening = data[i:i + 1]
    if opening == b"{":
        # Uniform: n{value}
        close = data.find(b"}", i)
        words = data[i + 1:close].replace(b"(", b" ").replace(b")", b" ")
        value = [float(w) for w in words.split()]
        return cls, value*n
    if opening != b"(":
        raise ValueError("%s: '(' expected after the count" % path)
    if binary:
        isLabel = cls == "labelList"
        size = labelBytes if isLabel else scalarBytes
        code = {4: "i", 8: "q"}[size] if isLabel else {4: "f", 8: "d"}[size]
        count = n*nComponents
        raw = data[i + 1:i + 1 + count*size]
        if len(raw) != count*size or data[i + 1 + count*size:i + 2 + count*size] != b")":
            raise ValueError("%s: truncated binary list" % path)
        return cls, list(struct.unpack("<%d%s" % (count, code), raw))
    close = data.rfind(b")")
    body = data[i + 1:close].replace(b"(", b" ").replace(b")", b" ")
    values = [float(w) for w in body.split()]
    if len(values) != n*nComponents:
        raise ValueError("%s: %d values, %d expected"
                         % (path, len(values), n*nComponents))
    return cls, values


# --------------------------------------------------------------------- VTK

_VTK_TYPES = {"Float64": "d", "Float32": "f", "Int64": "q", "Int32": "i",
              "Int16": "h", "Int8": "b", "UInt64": "Q", "UInt32": "I",
              "UInt16": "H", "UInt8": "B"}


def _lz4Block(src, size):
    """One LZ4 block (the raw block format VTK's vtkLZ4DataCompressor
    writes) decompressed to size bytes."""
    out = bytearray()
    i, n = 0, len(src)
    while i < n:
        token = src[i]
        i += 1
        literal = token >> 4
        if literal == 15:
            while True:
                b = src[i]
                i += 1
                literal += b
                if b != 255:
                    break
        out += src[i:i + literal]
        i += literal
        if i >= n:
            break
        offset = src[i] | (src[i + 1] << 8)
        i += 2
        match = token & 15
        if match == 15:
            while True:
                b = src[i]
                i += 1
                match += b
                if b != 255:
                    break
        match += 4
        begin = len(out) - offset
        if offset >= match:
            out += out[begin:begin + match]
        else:
            for k in range(match):
                out.append(out[begin + k])
    if len(out) != size:
        raise ValueError("lz4 block: %d bytes, %d expected" % (len(out), size))
    return bytes(out)


def _attributes(text):
    return dict(re.findall(r'(\w+)="([^"]*)"', text))


def readVtkArrays(path):
    """{section/name: [values]} of a VTK XML piece file."""
    data = _readBytes(path)
    appendedAt = data.find(b"<AppendedData")
    xml = data[:appendedAt if appendedAt >= 0 else len(data)].decode("latin-1")
    appended = b""
    encoding = "raw"
    if appendedAt >= 0:
        tagEnd = data.find(b">", appendedAt)
        encoding = _attributes(data[appendedAt:tagEnd].decode("latin-1")).get(
            "encoding", "raw")
        appended = data[data.find(b"_", tagEnd) + 1:]

    root = _attributes(re.search(r"<VTKFile([^>]*)>", xml).group(1))
    headerCode = {"UInt32": "I", "UInt64": "Q"}[root.get("header_type", "UInt32")]
    headerSize = struct.calcsize(headerCode)
    compressor = root.get("compressor", "")
    endian = "<" if root.get("byte_order", "LittleEndian") == "LittleEndian" else ">"

    def decodeBlocks(read):
        """The data of one array from read(offset, size) of its bytes."""
        if not compressor:
            (size,) = struct.unpack(endian + headerCode, read(0, headerSize))
            return read(headerSize, size)
        nBlocks, blockSize, lastSize = struct.unpack(
            endian + 3*headerCode, read(0, 3*headerSize))
        sizes = struct.unpack(endian + nBlocks*headerCode,
                              read(3*headerSize, nBlocks*headerSize))
        position = (3 + nBlocks)*headerSize
        out = b""
        for k, compressed in enumerate(sizes):
            full = lastSize if k == nBlocks - 1 and lastSize else blockSize
            chunk = read(position, compressed)
            position += compressed
            if "ZLib" in compressor:
                out += zlib.decompress(chunk)
            elif "LZ4" in compressor:
                out += _lz4Block(chunk, full)
            else:
                raise ValueError("%s: compressor %s not supported"
                                 % (path, compressor))
        return out

    arrays = {}
    section = ""
    sections = ("Points", "Cells", "Verts", "Lines", "Strips", "Polys",
                "PointData", "CellData", "FieldData")
    for m in re.finditer(r"<(/?)(\w+)([^>]*?)(/?)>", xml):
        closing, name, attrs, selfClosing = m.groups()
        if name in sections:
            section = "" if closing else name
            continue
        if name != "DataArray" or closing:
            continue
        a = _attributes(attrs)
        code = _VTK_TYPES[a["type"]]
        key = "%s/%s" % (section, a.get("Name", "?"))
        fmt = a.get("format", "ascii")
        if fmt == "ascii":
            text = xml[m.end():xml.find("</DataArray>", m.end())]
            # InformationKey elements (component names, ranges, with
            # nested Value elements) may come first
            text = re.sub(r"<InformationKey\b.*?</InformationKey>", " ", text,
                          flags=re.S)
            text = re.sub(r"<[^>]*>[^<]*</[^>]*>|<[^>]*/>", " ", text)
            convert = float if code in "df" else int
            values = [convert(w) for w in text.split()]
            if code == "f":
                # A Float32 written as text is read back as the float it
                # was (VTK 9.1 writes it with 17 digits; a writer of the
                # shortest text, 0.1, would otherwise read as another double)
                values = list(struct.unpack("<%df" % len(values),
                                            struct.pack("<%df" % len(values), *values)))
            arrays[key] = values
            continue
        if fmt != "appended" or encoding != "raw":
            raise ValueError("%s: %s data (encoding %s) not supported: only"
                             " what spemFoam writes" % (path, fmt, encoding))
        offset = int(a["offset"])
        read = lambda o, s, base=offset: appended[base + o:base + o + s]
        raw = decodeBlocks(read)
        count = len(raw)//struct.calcsize(code)
        arrays[key] = list(struct.unpack(endian + "%d%s" % (count, code), raw))
    return arrays
