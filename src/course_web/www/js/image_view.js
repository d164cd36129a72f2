// Draws a stream of image frames (the bridge's JPEG/PNG binary frames) on a canvas: a frame that
// arrives while the previous one is still decoding is skipped, and frames are counted per second
// (canvas.dataset.frames / .fps, read by the tests and the benchmark).
export function imageView(canvas, fpsLabel) {
  const context = canvas.getContext('2d');
  const drawn = frameCounter(canvas, fpsLabel);
  let drawing = false;
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
      drawn();
    }).catch(() => {}).finally(() => { drawing = false; });
  };
}

// Counts the pictures drawn on `canvas`: canvas.dataset.frames (all of them) and, each second,
// canvas.dataset.fps and the label's text. Returns the function to call after each picture.
export function frameCounter(canvas, fpsLabel) {
  let frames = 0;
  setInterval(() => {
    if (canvas.dataset.fps === String(frames)) { frames = 0; return; }  // nothing new to write (0 fps again)
    if (fpsLabel) fpsLabel.textContent = frames + ' fps';
    canvas.dataset.fps = String(frames);
    frames = 0;
  }, 1000);
  return function drawn() {
    frames += 1;
    canvas.dataset.frames = String(Number(canvas.dataset.frames || 0) + 1);
  };
}
