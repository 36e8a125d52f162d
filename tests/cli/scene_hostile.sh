#!/usr/bin/env bash
# Scene files as untrusted input (issue 22): special files, paths that leave the scene
# file's folder, URLs, missing references, and limits checked before the work they
# bound. Each case: `validate` exits 2 within seconds (no hang, no crash, no leak in the
# sanitizer build) with one message that names the file and what is wrong. No GL.
. "$(dirname "$0")/lib.sh"
cd "$T"
# gen.py KIND OUT [ARG]: a one-triangle glTF with a given buffer uri (buf), a chain of
# ARG nodes (deep), a texture (img), a byteLength (big); a PNG whose header says ARGxARG
# (png); the triangle's 36 bytes (raw)
cat >gen.py <<'PY'
import json, struct, zlib, base64, sys
def tri(uri=None, depth=1, image=None, bytelen=36):
    pos = struct.pack('<9f', 0, 0, 0, 1, 0, 0, 0, 1, 0)
    b64 = 'data:application/octet-stream;base64,'
    nodes = [{"children": [i + 1]} for i in range(depth - 1)] + [{"mesh": 0}]
    prim = {"attributes": {"POSITION": 0}}
    g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": nodes,
         "meshes": [{"primitives": [prim]}],
         "buffers": [{"uri": uri or b64 + base64.b64encode(pos).decode(), "byteLength": bytelen}],
         "bufferViews": [{"buffer": 0, "byteLength": 36}],
         "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                        "min": [0, 0, 0], "max": [1, 1, 0]}]}
    if image:
        uv = pos + struct.pack('<6f', 0, 0, 1, 0, 0, 1)
        g["buffers"][0] = {"uri": b64 + base64.b64encode(uv).decode(), "byteLength": 60}
        g["bufferViews"].append({"buffer": 0, "byteOffset": 36, "byteLength": 24})
        g["accessors"].append({"bufferView": 1, "componentType": 5126, "count": 3,
                               "type": "VEC2"})
        prim["attributes"]["TEXCOORD_0"] = 1
        prim["material"] = 0
        g["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
        g["textures"] = [{"source": 0}]
        g["images"] = [{"uri": image}]
    return json.dumps(g)
def png(w, h):
    def chunk(t, d):
        return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d))
    return (b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 2, 0, 0, 0))
            + chunk(b'IDAT', zlib.compress(b'\0' * 64)) + chunk(b'IEND', b''))
kind, out = sys.argv[1], sys.argv[2]
arg = sys.argv[3] if len(sys.argv) > 3 else None
if kind == 'raw': open(out, 'wb').write(struct.pack('<9f', 0, 0, 0, 1, 0, 0, 0, 1, 0))
elif kind == 'png': open(out, 'wb').write(png(int(arg), int(arg)))
else: open(out, 'w').write({'buf': lambda: tri(uri=arg), 'deep': lambda: tri(depth=int(arg)),
                            'img': lambda: tri(image=arg), 'big': lambda: tri(bytelen=int(arg))}[kind]())
PY
gen() { $PYTHON gen.py "$@"; }
manifest() {   # scene block -> m.yaml
  cat >m.yaml <<YAML
shadesweep: 1
name: hostile
scene: $1
renderers: [forward-spml]
resolution: 48x32
duration: {frames: 3}
clock: fixed
lights: {placement: random, count: 4, radius: 2}
YAML
}
refuse() {   # file, exact message after "scene.file: expected a scene file that loads, found "
  manifest "{file: $1}"
  local rc=0
  timeout 20 "$SHADESWEEP" validate m.yaml >out.txt 2>err.txt || rc=$?
  [ $rc -ne 124 ] || fail "$1: validate hung"
  [ $rc -eq 2 ] || fail "$1: exit $rc, want 2: $(cat err.txt)"
  local want="m.yaml:3:15: scene.file: expected a scene file that loads, found $2"
  [ "$(cat err.txt)" = "$want" ] || fail "$1: got: $(cat err.txt)
want: $want"
}
mkdir -p s
gen raw s/tri.bin
gen raw outside.bin
gen buf s/ok.gltf tri.bin
manifest "{file: s/ok.gltf}"
"$SHADESWEEP" validate m.yaml >v.txt 2>&1 || fail "a plain buffer file: $(cat v.txt)"

# special files, as the scene and as what it references: refused by name, never opened
mkfifo fifo.gltf s/fifo.bin s/fifo.png
refuse fifo.gltf "fifo.gltf: a FIFO, not a regular file"
mkdir dir.gltf
refuse dir.gltf "dir.gltf: a directory, not a regular file"
gen buf s/fifob.gltf fifo.bin
refuse s/fifob.gltf "s/fifob.gltf: s/fifo.bin: a FIFO, not a regular file"
gen img s/fifoi.gltf fifo.png
refuse s/fifoi.gltf "s/fifoi.gltf: s/fifo.png: a FIFO, not a regular file"

# leaving the scene file's folder: .., an absolute path, a symlink; a URL
root=$(cd s && pwd -P)
gen buf s/up.gltf ../outside.bin
refuse s/up.gltf "s/up.gltf: s/../outside.bin: resolves to $(pwd -P)/outside.bin, outside the scene file's folder $root (scene.allow_outside: true permits it)"
gen buf s/abs.gltf "$T/outside.bin"
refuse s/abs.gltf "s/abs.gltf: uri '$T/outside.bin' is an absolute path: a uri is relative to the file's folder"
ln -s ../outside.bin s/link.bin
gen buf s/sym.gltf link.bin
refuse s/sym.gltf "s/sym.gltf: s/link.bin: resolves to $(pwd -P)/outside.bin, outside the scene file's folder $root (scene.allow_outside: true permits it)"
cp s/tri.bin tri.bin   # what assimp used to read instead of the URL
gen buf s/http.gltf http://example.com/tri.bin
refuse s/http.gltf "s/http.gltf: uri 'http://example.com/tri.bin' is a URL: only local files are read"
printf 'mtllib ../up.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >s/upmtl.obj
printf 'newmtl a\nKd 1 0 0\n' >up.mtl
refuse s/upmtl.obj "s/upmtl.obj: s/../up.mtl: resolves to $(pwd -P)/up.mtl, outside the scene file's folder $root (scene.allow_outside: true permits it)"

# every referenced file must exist: a missing .mtl as a missing buffer
printf 'mtllib nothere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >s/nomtl.obj
refuse s/nomtl.obj "s/nomtl.obj: references s/nothere.mtl, which does not exist"
gen buf s/miss.gltf nothere.bin
refuse s/miss.gltf "s/miss.gltf: references s/nothere.bin, which does not exist"

# refusals that name their cause (issue 25): a file of points, of lines or of bare
# vertices, and a text encoding assimp does not read; an MTL path written with Windows
# separators (".\wall.png", the file beside it) loads
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\np 1 2 3\n' >s/points.obj
refuse s/points.obj "s/points.obj: cannot load: it has only points and lines (1 mesh of points, 0 of lines), and shadesweep draws triangles"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3\n' >s/lines.obj
refuse s/lines.obj "s/lines.obj: cannot load: it has only points and lines (0 meshes of points, 1 of lines), and shadesweep draws triangles"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\n' >s/cloud.obj
refuse s/cloud.obj "s/cloud.obj: cannot load: it has only points and lines (1 mesh of points, 0 of lines), and shadesweep draws triangles"
$PYTHON -c "open('s/utf16.obj', 'wb').write(b'\xff\xfe' + 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n'.encode('utf-16-le'))"
refuse s/utf16.obj "s/utf16.obj: cannot load: the file is UTF-16 (little-endian) text (its byte-order mark says so), which assimp does not read: save it as UTF-8 (iconv -f UTF-16 -t UTF-8)"
# only the importers of the file's own format: a .gltf that the glTF importers decline
# is not offered to the other 50 (assimp's OpenGEX importer, whose signature test finds
# "GeometryNode" here, read past its buffer); an extension shadesweep does not read is
# refused before assimp sees the bytes, and the case of one does not matter
printf 'Metric {} GeometryNode { Mesh { VertexArray {} IndexArray {} } }\n' >s/ogex.gltf
refuse s/ogex.gltf "s/ogex.gltf: cannot load: not a glTF file that assimp reads (no other format is tried for a .gltf file)"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >s/tri.fbx
refuse s/tri.fbx "s/tri.fbx: cannot load: the extension '.fbx' is not one shadesweep reads: .gltf, .glb (glTF 2.0) or .obj (Wavefront OBJ)"
cp s/tri.fbx s/tri
refuse s/tri "s/tri: cannot load: the file has no extension, not one shadesweep reads: .gltf, .glb (glTF 2.0) or .obj (Wavefront OBJ)"
cp s/tri.fbx s/TRI.OBJ
manifest "{file: s/TRI.OBJ}"
"$SHADESWEEP" validate m.yaml >v.txt 2>&1 || fail "an .OBJ in capitals: $(cat v.txt)"
# an mtllib path with a ':' (a URL or a drive letter; one ending in "://" made assimp's
# OBJ importer erase a negative length) is refused before assimp reads the file, also
# where a backslash continues its line
printf 'mtllib m.mtl://\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >s/url.obj
refuse s/url.obj "s/url.obj: mtllib 'm.mtl://' has a ':' (a URL or a drive letter): a material library is named relative to the .obj's folder"
printf 'mtllib c\\\n:/m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >s/drive.obj
refuse s/drive.obj "s/drive.obj: mtllib 'c\\?:/m.mtl' has a ':' (a URL or a drive letter): a material library is named relative to the .obj's folder"
# a statement before a material library's first newmtl: assimp 5.2 wrote through a null
# material for an "a..." line (scripts/fuzz.sh found it) and for any texture map; the
# library is refused by name whatever the name of the file (here .bin) and its line shown
printf 'mtllib m.bin\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >s/pre.obj
printf '# made by hand\n\n  aniso 1\nnewmtl a\n' >s/m.bin
refuse s/pre.obj "s/pre.obj: s/m.bin: line 3 'aniso 1' comes before the first newmtl: a material statement needs a material"
printf 'map_Kd x.png\r\nnewmtl a\r\n' >s/m.bin
refuse s/pre.obj "s/pre.obj: s/m.bin: line 1 'map_Kd x.png' comes before the first newmtl: a material statement needs a material"
printf '\xff\xfen\0e\0' >s/m.bin
refuse s/pre.obj "s/pre.obj: s/m.bin: a material library in UTF-16 or UTF-32: write it as UTF-8"
printf '\xef\xbb\xbf# ok\n\tNEWMTL a\nmap_Kd x.png\n' >s/m.bin
manifest "{file: s/pre.obj}"
"$SHADESWEEP" validate m.yaml >v.txt 2>&1 && fail "a NEWMTL is not newmtl: $(cat v.txt)"
printf '\xef\xbb\xbf# ok\n\tnewmtl a\nKd 1 0 0\na 0.5\n' >s/m.bin
"$SHADESWEEP" validate m.yaml >v.txt 2>&1 || fail "a material library after its newmtl: $(cat v.txt)"
mkdir -p s/win
gen png s/win/wall.png 4
printf 'mtllib win.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3\n' >s/win/win.obj
printf 'newmtl a\nKd 1 1 1\nmap_Kd .\\wall.png\n' >s/win/win.mtl
grep -qF '.\wall.png' s/win/win.mtl || fail "the test's MTL lost its backslash: $(cat s/win/win.mtl)"
manifest "{file: s/win/win.obj}"
"$SHADESWEEP" validate m.yaml >v.txt 2>&1 || fail "an MTL path with backslashes: $(cat v.txt)"

# limits before the work: a 100000-deep node chain (assimp's recursion overflowed the
# stack), a PNG whose header says 100000x100000 (decoded in full before), a byteLength
# of 4 GB (its refusal leaked the importer's stream)
gen deep s/deep.gltf 100000
refuse s/deep.gltf "s/deep.gltf: the node hierarchy is 100000 deep, more than 255"
gen png s/huge.png 100000
gen img s/huge.gltf huge.png
refuse s/huge.gltf "s/huge.gltf: texture 'huge.png' is 100000x100000, more than 8192 texels a side"
gen big s/big.gltf 4000000000
refuse s/big.gltf "s/big.gltf: cannot load: GLTF: buffer \"buffers[0]\", expected 4000000000 bytes, but found 48"
$PYTHON - <<'PY'
n = 100000   # JSON nested deeper than assimp's recursive parser should go, where nodes go
open("s/nest.gltf", "w").write('{"asset": {"version": "2.0"}, "nodes": ' + "[" * n + "]" * n + "}")
PY
refuse s/nest.gltf "s/nest.gltf: JSON nested more than 64 deep"
$PYTHON - <<'PY'
import struct   # a .glb whose JSON chunk claims 128 MiB (assimp cleared that much first)
body = struct.pack('<I', 1 << 27) + b'JSON' + b'{}  '
open("s/claims.glb", "wb").write(b'glTF' + struct.pack('<II', 2, 12 + len(body)) + body)
PY
refuse s/claims.glb "s/claims.glb: GLB chunk 0 claims 134217728 bytes, 4 follow it"
# the limits let through what they should: a chain of 200 nodes, a 4x4 texture
gen deep s/deep200.gltf 200
gen png s/small.png 4
gen img s/small.gltf small.png
for f in s/deep200.gltf s/small.gltf; do
  manifest "{file: $f}"
  "$SHADESWEEP" validate m.yaml >v.txt 2>&1 || fail "$f: $(cat v.txt)"
done

# scene.allow_outside: true lets a file reference what lies outside its folder (the id
# is the content's either way: the key does not change it); anything but a boolean is
# refused
manifest "{file: s/ok.gltf}"
"$SHADESWEEP" list m.yaml >ids1.txt
manifest "{file: s/ok.gltf, allow_outside: true}"
"$SHADESWEEP" list m.yaml >ids2.txt
cmp -s ids1.txt ids2.txt || fail "allow_outside changed the id: $(cat ids1.txt ids2.txt)"
for f in s/up.gltf s/sym.gltf s/upmtl.obj; do
  manifest "{file: $f, allow_outside: true}"
  "$SHADESWEEP" validate m.yaml >v.txt 2>&1 || fail "$f with allow_outside: $(cat v.txt)"
done
manifest "{file: s/up.gltf, allow_outside: yes}"
rc=0; "$SHADESWEEP" validate m.yaml >out.txt 2>err.txt || rc=$?
[ $rc -eq 2 ] && grep -qx "m.yaml:3:41: scene.allow_outside: expected one of false, true, found 'yes'" err.txt ||
  fail "allow_outside: yes: exit $rc: $(cat err.txt)"
# scale: fit or a number > 0; light_bounds: around or model
for bad in "scale: fat|m.yaml:3:33: scene.scale: expected fit or a number > 0 and <= 1e+09, found 'fat'" \
           "scale: 0|m.yaml:3:33: scene.scale: expected a number > 0 and <= 1e+09, found '0'" \
           "light_bounds: inside|m.yaml:3:40: scene.light_bounds: expected one of around, model, found 'inside'"; do
  manifest "{file: s/ok.gltf, ${bad%%|*}}"
  rc=0; "$SHADESWEEP" validate m.yaml >out.txt 2>err.txt || rc=$?
  [ $rc -eq 2 ] && grep -qxF "${bad#*|}" err.txt || fail "${bad%%|*}: exit $rc: $(cat err.txt)"
done

# issue 39: bounds from what a file says, before the work, each naming the limit a
# manifest can raise (scene.max_image_bytes, max_triangles, max_vertices): an .obj's
# faces counted before assimp (a polygon of n corners is n - 2 triangles), a texture's
# decoded bytes from its header (a TIFF whose sides pass but whose 100 channels ask for
# 1.6 GB); a limit let through at its value, and none of them part of the id
$PYTHON - <<'PY'
import struct, zlib
tri = 'v 0 0 0\nv 1 0 0\nv 0 1 0\n'
open('s/many.obj', 'w').write(tri + 'f 1 2 3\n' * 2000)
open('s/poly.obj', 'w').write(tri + 'f ' + ' '.join(['1 2 3'] * 400) + '\n')
open('s/huge.obj', 'w').write('v -3e38 0 0\nv 3e38 0 0\nv 0 3e38 0\nf 1 2 3\n')
def tiff(w, h, spp):   # a header only: what the probe reads
    e = [(256, 4, w), (257, 4, h), (258, 3, 8), (259, 3, 1), (262, 3, 1), (273, 4, 8),
         (277, 3, spp), (278, 4, h), (279, 4, w * h * spp), (284, 3, 1)]
    ifd = struct.pack('<H', len(e)) + b''.join(
        struct.pack('<HHI', t, k, 1) + (struct.pack('<HH', v, 0) if k == 3 else struct.pack('<I', v))
        for t, k, v in e) + struct.pack('<I', 0)
    return b'II*\0' + struct.pack('<I', 8) + ifd
def png(w, h):
    def chunk(t, d):
        return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d))
    raw = b''.join(b'\0' + b'\x80' * (3 * w) for _ in range(h))
    return (b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 2, 0, 0, 0))
            + chunk(b'IDAT', zlib.compress(raw)) + chunk(b'IEND', b''))
open('s/wide.tif', 'wb').write(tiff(4096, 4096, 100))
open('s/t64.png', 'wb').write(png(64, 64))
open('s/cut.png', 'wb').write(png(64, 64)[:60])
for name, img in (('wide', 'wide.tif'), ('t64', 't64.png'), ('cut', 'cut.png')):
    open(f's/{name}.mtl', 'w').write(f'newmtl a\nKd 1 1 1\nmap_Kd {img}\n')
    open(f's/{name}.obj', 'w').write(f'mtllib {name}.mtl\n' + tri +
        'vt 0 0\nvt 1 0\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3\n')
PY
refuse_with() {   # scene block, column, exact message after "found "
  manifest "$1"
  local rc=0
  timeout 20 "$SHADESWEEP" validate m.yaml >out.txt 2>err.txt || rc=$?
  [ $rc -eq 2 ] || fail "$1: exit $rc, want 2: $(cat err.txt)"
  local want="m.yaml:3:$2: scene.file: expected a scene file that loads, found $3"
  [ "$(cat err.txt)" = "$want" ] || fail "$1: got: $(cat err.txt)
want: $want"
}
refuse_with "{file: s/many.obj, max_triangles: 1999}" 15 "s/many.obj: 2000 triangles, more than scene.max_triangles 1999"
refuse_with "{file: s/poly.obj, max_triangles: 1000}" 15 "s/poly.obj: 1198 triangles, more than scene.max_triangles 1000"
refuse_with "{file: s/many.obj, max_vertices: 2}" 15 "s/many.obj: 3 vertices, more than scene.max_vertices 2"
refuse s/wide.obj "s/wide.obj: texture 'wide.tif' is 4096x4096 with 100 channels, 1677721600 bytes decoded, more than scene.max_image_bytes 1073741824"
refuse_with "{file: s/t64.obj, max_image_bytes: 12287}" 15 "s/t64.obj: texture 't64.png' is 64x64 with 3 channels, 12288 bytes decoded, more than scene.max_image_bytes 12287"
manifest "{file: s/t64.obj}"
"$SHADESWEEP" list m.yaml >ids1.txt
for ok in "s/many.obj, max_triangles: 2000" "s/many.obj, max_vertices: 3" \
          "s/t64.obj, max_image_bytes: 12288"; do
  manifest "{file: $ok}"
  "$SHADESWEEP" validate m.yaml >v.txt 2>&1 || fail "$ok: $(cat v.txt)"
done
"$SHADESWEEP" list m.yaml >ids2.txt
cmp -s ids1.txt ids2.txt || fail "max_image_bytes changed the id: $(cat ids1.txt ids2.txt)"
manifest "{file: s/many.obj, max_triangles: 0}"
rc=0; "$SHADESWEEP" validate m.yaml >out.txt 2>err.txt || rc=$?
[ $rc -eq 2 ] && grep -qxF "m.yaml:3:42: scene.max_triangles: expected an integer 1..9007199254740992, found '0'" err.txt ||
  fail "max_triangles: 0: exit $rc: $(cat err.txt)"
# messages that name the real cause: huge but finite coordinates (3e38 was "zero area"),
# a PNG cut off (refused before libpng, which printed a line of its own and leaked)
refuse s/huge.obj "s/huge.obj: mesh 0 ('defaultobject'): vertex 0 has a position too large for 32-bit float arithmetic (-3e+38, 0, 0): at most 1e+18 a coordinate"
refuse s/cut.obj "s/cut.obj: texture 'cut.png' does not decode: s/cut.png: cannot read image: cut off: its IDAT chunk claims 192 bytes, 15 follow"

# the manifest itself as a scene file is: anything but a regular file is refused by
# name (a FIFO hung validate; a directory read "Input/output error"), and UTF-16 is
# refused by validate, naming the encoding (run failed later, in its YAML writer)
mkdir mdir.yaml
mkfifo mfifo.yaml
for m in mdir.yaml:directory mfifo.yaml:FIFO; do
  rc=0; timeout 20 "$SHADESWEEP" validate "${m%%:*}" >out.txt 2>err.txt || rc=$?
  [ $rc -eq 2 ] && [ "$(cat err.txt)" = "${m%%:*}: expected a manifest file, found a ${m#*:}, not a regular file" ] ||
    fail "${m%%:*} as the manifest: exit $rc: $(cat err.txt)"
done
manifest "{file: s/ok.gltf}"
$PYTHON -c "open('m16.yaml', 'wb').write(b'\xff\xfe' + open('m.yaml').read().encode('utf-16-le'))"
rc=0; "$SHADESWEEP" validate m16.yaml >out.txt 2>err.txt || rc=$?
[ $rc -eq 2 ] && [ "$(cat err.txt)" = "m16.yaml: expected UTF-8 text, found UTF-16 (little-endian) (its byte-order mark says so): save it as UTF-8 (iconv -f UTF-16 -t UTF-8)" ] ||
  fail "a UTF-16 manifest: exit $rc: $(cat err.txt)"
