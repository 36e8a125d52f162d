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
