// Products downlinked by petra-fsw and reassembled by the server:
// GET /api/product/<kind> gives the raw bytes and their shape in headers.
//   format 1: gray8 rows, 2: rgb8 rows, 3: xyz float32 mm triples, big-endian.

export async function fetchProduct(kind) {
  const r = await fetch(`/api/product/${kind}`, { cache: 'no-store' });
  if (!r.ok) return null;
  return {
    kind,
    width: Number(r.headers.get('X-Petra-Width')),
    height: Number(r.headers.get('X-Petra-Height')),
    format: Number(r.headers.get('X-Petra-Format')),
    id: Number(r.headers.get('X-Petra-Id')),
    bytes: new Uint8Array(await r.arrayBuffer()),
  };
}

// Image products as RGBA pixels; null when the shape and size disagree.
export function toImageData(p) {
  const n = p.width * p.height;
  const channels = p.format === 2 ? 3 : 1;
  if (p.format > 2 || n <= 0 || p.bytes.length < n * channels) return null;
  const img = new ImageData(p.width, p.height);
  for (let i = 0; i < n; ++i) {
    const s = i * channels;
    img.data[i * 4] = p.bytes[s];
    img.data[i * 4 + 1] = p.bytes[s + (channels - 1 ? 1 : 0)];
    img.data[i * 4 + 2] = p.bytes[s + (channels - 1 ? 2 : 0)];
    img.data[i * 4 + 3] = 255;
  }
  return img;
}

export function drawImageProduct(canvas, p) {
  const img = toImageData(p);
  if (!img) return false;
  canvas.width = p.width;
  canvas.height = p.height;
  canvas.getContext('2d').putImageData(img, 0, 0);
  return true;
}

// Point cloud: Float32Array x,y,z (mm) in the calibration world frame.
export function toPoints(p) {
  if (p.format !== 3 || p.bytes.length % 12 !== 0) return null;
  const view = new DataView(p.bytes.buffer, p.bytes.byteOffset, p.bytes.byteLength);
  const out = new Float32Array(p.bytes.length / 4);
  for (let i = 0; i < out.length; ++i) out[i] = view.getFloat32(i * 4, false);
  return out;
}
