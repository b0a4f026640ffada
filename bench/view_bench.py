#!/usr/bin/env python3
"""`simbob view` pages of N bodies x 1000 samples: size against the raw float32 pose data, time
to open in headless Chromium, frame rate while playing (issue #23, point 5).

Usage: /usr/bin/python3 bench/view_bench.py [build/simbob] [N ...]   (default N: 10 100 1000)

The scene is bench/gen_scene.py's grid of N boxes; the trajectory is written here (each box
circling and spinning about its place, 1000 samples 0.01 s apart) rather than simulated, since
resting boxes would be a still picture. Chromium runs as in tests/view/browser_test.py
(headless, SwiftShader WebGL, no network). Open time: from asking for the page until the viewer
reports ready (three.js parsed, scene built, poses decoded, first frame drawn), median of 3.
Frame rate: frames drawn while playing at 1x for 3 s, as the page opens by default (alike
bodies instanced, antialiasing off from 100 bodies on), and drawn body by body with
antialiasing (#inst=0&aa=1, as the page drew before instancing). Draw ms: the page's own work
for one frame (seek: poses set, instance matrices written, three.js's render call issued),
mean of 20, in both modes; what WebGL then costs in Chromium's GPU process is not in it.
The viewer's own timings (ms after navigation) say where the opening time goes. Figures go to
stdout.
"""
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

sys.dont_write_bytecode = True
from selenium import webdriver  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'tests', 'view'))
from chromedriver import LocalService  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SIMBOB = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, '..', 'build', 'simbob')
COUNTS = [int(a) for a in sys.argv[2:]] or [10, 100, 1000]
SAMPLES = 1000


def write_csv(path, keys, samples):
    with open(path, 'w') as f:
        f.write('time,body,x,y,z,qw,qx,qy,qz\n')
        for s in range(samples):
            t = s * 0.01
            for i, key in enumerate(keys):
                x0, z0 = (i % 32) * 0.3, (i // 32) * 0.3
                a = t + i * 0.1
                f.write(f'{round(t, 2)!r},{key},{x0 + 0.1 * math.cos(a)!r},{0.101 + 0.05 * math.sin(2 * a)!r},'
                        f'{z0 + 0.1 * math.sin(a)!r},{math.cos(a / 2)!r},0,{math.sin(a / 2)!r},0\n')


def browser():
    o = webdriver.ChromeOptions()
    for a in ['--headless=new', '--no-sandbox', '--disable-dev-shm-usage', '--use-angle=swiftshader',
              '--enable-unsafe-swiftshader', '--window-size=1000,700', '--host-resolver-rules=MAP * ~NOTFOUND',
              '--proxy-server=127.0.0.1:9']:
        o.add_argument(a)
    return webdriver.Chrome(service=LocalService(), options=o)


def open_time(d, page, fragment=''):
    d.get('about:blank')
    start = time.monotonic()
    d.get('file://' + page + fragment)
    while not d.execute_script('return !!(window.simbobView && window.simbobView.ready)'):
        time.sleep(0.005)
    return time.monotonic() - start


def fps(d):
    """Frames drawn per second while playing at 1x for 3 s."""
    d.execute_script("document.getElementById('speed').value = '1'; simbobView.seek(0); simbobView.play()")
    f0, t0 = d.execute_script('return simbobView.frames()'), time.monotonic()
    time.sleep(3)
    f1, t1 = d.execute_script('return simbobView.frames()'), time.monotonic()
    return (f1 - f0) / (t1 - t0)


def draw_ms(d):
    return d.execute_script('const t = performance.now(); for (let i = 0; i < 20; ++i) simbobView.seek(i * 0.01);'
                            'return (performance.now() - t) / 20')


def main():
    work = tempfile.mkdtemp(prefix='simbob-view-bench.')
    d = browser()
    print(f'simbob view: pages of N bodies x {SAMPLES} samples, headless Chromium (SwiftShader), '
          f'{os.cpu_count()} CPUs')
    print('bodies  page_bytes  raw_f32_bytes  fixed_bytes  (page-fixed)/raw  open_s_median  fps_playing  fps_each_aa  draw_ms  draw_ms_each'
          '   ms_after_navigation: script_start parsed decoded built first_frame')
    try:
        for n in COUNTS:
            scene = os.path.join(work, f'boxes{n}.xml')
            subprocess.run([sys.executable, os.path.join(HERE, 'gen_scene.py'), str(n), scene], check=True)
            keys = [f'Box{i}' for i in range(n)]
            csv, one = os.path.join(work, f'boxes{n}.csv'), os.path.join(work, f'boxes{n}_1.csv')
            write_csv(csv, keys, SAMPLES)
            write_csv(one, keys, 1)
            page, fixed_page = os.path.join(work, f'boxes{n}.html'), os.path.join(work, f'boxes{n}_1.html')
            for c, p in ((csv, page), (one, fixed_page)):
                subprocess.run([SIMBOB, 'view', c, '--scene', scene, '-o', p, '-q'], check=True)
            size, raw = os.path.getsize(page), n * SAMPLES * 7 * 4
            # The fixed part: the same page with one sample (three.js, the viewer, the scene).
            fixed = os.path.getsize(fixed_page) - n * 7 * 4 * 4 // 3
            opens = [open_time(d, page) for _ in range(3)]
            steps = d.execute_script('const t = simbobView.timings; return [t.start, t.parsed, t.decoded, t.built, t.drawn]')
            rate = fps(d)
            ms = draw_ms(d)
            open_time(d, page, '#inst=0&aa=1')
            rate_each = fps(d)
            ms_each = draw_ms(d)
            print(f'{n:6d}  {size:10d}  {raw:13d}  {fixed:11d}  {(size - fixed) / raw:15.3f}  '
                  f'{statistics.median(opens):13.2f}  {rate:11.1f}  {rate_each:11.1f}  {ms:7.1f}  {ms_each:12.1f}   '
                  + ' '.join(f'{v:.0f}' for v in steps))
    finally:
        d.quit()


main()
