// pinframes page: builds the meshcat scene from the embedded commands and adds the
// controls: play/pause, a time slider, the time shown, frame and link names on or off, and
// the closest pair of a clearance when the page marks one.
// window.pinframes.seek(seconds) and .ready serve scripted use (the browser tests).
(function () {
  "use strict";
  const data = JSON.parse(document.getElementById("pinframes-data").textContent);
  const pane = document.getElementById("meshcat-pane");
  const viewer = new MeshCat.Viewer(pane);
  for (const command of data.commands) {
    const bytes = Uint8Array.from(atob(command), (c) => c.charCodeAt(0));
    viewer.handle_command_bytearray(bytes);
  }
  const THREE = MeshCat.THREE;
  const animator = viewer.animator;
  const duration = data.duration;
  // meshcat schedules its actions only when playing starts; seeking needs them scheduled
  for (const action of animator.actions) action.play();

  // camera: z up in meshcat's "rotated" camera frame, whose (x, y, z) is world (x, z, -y)
  const c = data.centre, r = data.radius;
  const toCamera = (x, y, z) => new THREE.Vector3(x, z, -y);
  viewer.camera.position.copy(toCamera(c[0] + 1.3 * r, c[1] + 0.75 * r, c[2] + 0.65 * r));
  viewer.controls.target.copy(toCamera(c[0], c[1], c[2]));
  viewer.camera.far = 100 * r;
  viewer.controls.update();
  viewer.set_dirty();

  // the controls bar
  const bar = document.createElement("div");
  bar.id = "pinframes-controls";
  bar.innerHTML =
    '<button id="pinframes-play" type="button">play</button>' +
    '<input id="pinframes-slider" type="range" min="0" step="any">' +
    '<span id="pinframes-time"></span>' +
    '<label><input id="pinframes-frame-names" type="checkbox" checked> frame names</label>' +
    '<label><input id="pinframes-link-names" type="checkbox"> link names</label>' +
    '<span id="pinframes-clearance"></span>';
  document.body.appendChild(bar);
  const play = document.getElementById("pinframes-play");
  const slider = document.getElementById("pinframes-slider");
  const shown = document.getElementById("pinframes-time");
  slider.max = String(duration);
  slider.value = "0";
  slider.disabled = duration <= 0;
  play.disabled = duration <= 0;

  function currentTime() {
    return animator.actions.length ? animator.time : 0;
  }
  // the closest pair of a clearance, if the page marks one: its distance and frames at the
  // last sample at or before t
  const clearance = data.clearance;
  const closest = document.getElementById("pinframes-clearance");
  function showClearance(t) {
    if (!clearance) return;
    const seconds = clearance.seconds;
    let low = 0, high = seconds.length - 1;
    while (low < high) {
      const middle = (low + high + 1) >> 1;
      if (seconds[middle] <= t + 1e-9) low = middle; else high = middle - 1;
    }
    const pair = clearance.pairs[low];
    const distance = clearance.distanceMm[low];
    closest.textContent = "closest: " + distance.toFixed(1) + " mm, " +
      clearance.names[pair[0]] + " \u2013 " + clearance.names[pair[1]] +
      (distance <= 0 ? " (contact)" : "");
    closest.className = distance <= 0 ? "pinframes-contact" : "";
  }
  function showTime(t) {
    shown.textContent = "t = " + t.toFixed(3) + " s of " + duration.toFixed(3) +
      " s (start " + data.start + ")";
    showClearance(t);
  }
  function seek(t) {
    t = Math.max(0, Math.min(duration, t));
    if (animator.actions.length) {
      animator.seek(t);
      animator.display_progress(t);
    }
    slider.value = String(t);
    showTime(t);
    viewer.set_dirty();
  }
  function setPlaying(on) {
    if (on) {
      if (currentTime() >= duration) seek(0);
      for (const action of animator.actions) action.paused = false;  // clamped at the end
      animator.play();
    } else {
      animator.pause();
    }
    play.textContent = on ? "pause" : "play";
  }
  play.addEventListener("click", () => setPlaying(!animator.playing));
  slider.addEventListener("input", () => {
    if (animator.playing) setPlaying(false);
    seek(parseFloat(slider.value));
  });

  // frame names: HTML labels placed where each frame's origin is on the screen
  const LABEL_OFFSET = 6;  // px right of the origin
  const labels = data.labels.map((label) => {
    const element = document.createElement("div");
    element.className = "pinframes-label";
    element.textContent = label.text;
    document.body.appendChild(element);
    const node = viewer.scene_tree.find(label.path.split("/").filter((s) => s.length));
    return { element: element, object: node.object, link: label.link };
  });
  const frameNames = document.getElementById("pinframes-frame-names");
  const linkNames = document.getElementById("pinframes-link-names");
  const origin = new THREE.Vector3();
  function placeLabels() {
    const width = pane.clientWidth, height = pane.clientHeight;
    const shown = [];  // the visible labels and the screen point of their frame's origin
    for (const label of labels) {
      const on = label.link ? linkNames.checked : frameNames.checked;
      label.object.getWorldPosition(origin);
      origin.project(viewer.camera);
      const visible = on && origin.z < 1 && Math.abs(origin.x) <= 1 && Math.abs(origin.y) <= 1;
      label.element.style.display = visible ? "block" : "none";
      if (visible) {
        shown.push({ label: label, x: (origin.x + 1) / 2 * width,
                     y: (1 - origin.y) / 2 * height });
      }
    }
    // frames whose origins are close (a tool on its target, a seam point) would print their
    // names over each other: from the top of the screen down, a label that meets one already
    // placed moves below it
    shown.sort((a, b) => a.y - b.y || a.x - b.x);
    const placed = [];
    for (const item of shown) {
      const element = item.label.element;
      const w = element.offsetWidth, h = element.offsetHeight;
      const left = item.x + LABEL_OFFSET;
      let top = item.y - h / 2;
      for (let moved = true; moved;) {
        moved = false;
        for (const box of placed) {
          if (left < box.right && left + w > box.left && top < box.bottom && top + h > box.top) {
            top = box.bottom + 1;
            moved = true;
          }
        }
      }
      placed.push({ left: left, top: top, right: left + w, bottom: top + h });
      element.style.left = left + "px";
      element.style.top = top + "px";
    }
  }
  frameNames.addEventListener("change", placeLabels);
  linkNames.addEventListener("change", placeLabels);

  function tick() {
    if (animator.playing) {
      const t = currentTime();
      slider.value = String(t);
      showTime(t);
      if (t >= duration) setPlaying(false);
    }
    placeLabels();
    requestAnimationFrame(tick);
  }
  seek(0);
  requestAnimationFrame(tick);
  window.pinframes = {
    seek: seek,
    play: () => setPlaying(true),
    pause: () => setPlaying(false),
    duration: duration,
    labelCount: () => labels.filter((l) => l.element.style.display === "block").length,
    viewer: viewer,
    ready: true,
  };
})();
