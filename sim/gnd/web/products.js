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

// "#rrggbb" -> [r, g, b].
const rgbOf = (hex) => [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16));

// The disparity colour map of tlm/palette.hpp at t in [0, 1] (0 far, 1 near):
// linear between equally spaced stops, as palette::disparity_colour.
export function rampColour(palette, t) {
  const stops = palette.disparity_ramp.map(rgbOf);
  const x = Math.min(Math.max(t, 0), 1) * (stops.length - 1);
  const i = Math.min(Math.floor(x), stops.length - 2);
  const f = x - i;
  return stops[i].map((a, k) => Math.trunc(a + f * (stops[i + 1][k] - a)));
}

// The disparity product (gray 1..255 from the smallest to the largest match,
// 0 where none) in the palette's colours, as `petra eval`'s disparity.png.
export function drawDisparity(canvas, p, palette) {
  const img = toImageData(p);
  if (!img || p.format !== 1) return false;
  const none = rgbOf(palette.no_data);
  for (let i = 0; i < p.width * p.height; ++i) {
    const g = p.bytes[i];
    const c = g === 0 ? none : rampColour(palette, (g - 1) / 254);
    img.data.set(c, i * 4);
  }
  canvas.width = p.width;
  canvas.height = p.height;
  canvas.getContext('2d').putImageData(img, 0, 0);
  return true;
}

export function drawColourBar(canvas, palette) {
  canvas.width = 256;
  canvas.height = 1;
  const img = new ImageData(256, 1);
  for (let x = 0; x < 256; ++x) img.data.set([...rampColour(palette, x / 255), 255], x * 4);
  canvas.getContext('2d').putImageData(img, 0, 0);
}

// Point cloud: Float32Array x,y,z (mm) in the calibration world frame.
export function toPoints(p) {
  if (p.format !== 3 || p.bytes.length % 12 !== 0) return null;
  const view = new DataView(p.bytes.buffer, p.bytes.byteOffset, p.bytes.byteLength);
  const out = new Float32Array(p.bytes.length / 4);
  for (let i = 0; i < out.length; ++i) out[i] = view.getFloat32(i * 4, false);
  return out;
}
