// Draws a stream of image frames (the bridge's JPEG/PNG binary frames) on a canvas: a frame that
// arrives while the previous one is still decoding is skipped, and frames are counted per second
// (canvas.dataset.frames / .fps, read by the tests and the benchmark).
export function imageView(canvas, fpsLabel) {
  const context = canvas.getContext('2d');
  let frames = 0;
  let drawing = false;
  setInterval(() => {
    if (fpsLabel) fpsLabel.textContent = frames + ' fps';
    canvas.dataset.fps = String(frames);
    frames = 0;
  }, 1000);
  return function draw(blob, header) {
    if (drawing) return;
    drawing = true;
    createImageBitmap(blob).then((bitmap) => {
      if (canvas.width !== header.width || canvas.height !== header.height) {
        canvas.width = header.width;
        canvas.height = header.height;
      }
      context.drawImage(bitmap, 0, 0);
      bitmap.close();
      frames += 1;
      canvas.dataset.frames = String(Number(canvas.dataset.frames || 0) + 1);
    }).catch(() => {}).finally(() => { drawing = false; });
  };
}
