"""simbob view pages in a real browser (issue #23): Debian's chromium, headless, driven through
chromium-driver by python3-selenium; pages opened from file:// with the network cut off.

  /usr/bin/python3 browser_test.py SIMBOB REPO CASE WORKDIR

CASE is one of
  scenes      every scene in scenes/ runs briefly, its page opens without a console error, and
              at three times set through the URL fragment every body's pose read back from the
              page equals the CSV row rounded to float32
  screenshot  tests/data/view/colors.xml: the page's canvas and `simbob render` of the same
              camera put each body's colour centre within a few pixels, at three times
  ui          the controls: fragment, click to select, step, play, speed, loop, pause, trails
  gallery     `sweep gather --html`: rows, links to the case pages, marks, sorting, the plot
  golden      a chain against a run with a heavier link: ghosts at the golden poses, the slider's
              divergence marker at the time `simbob compare` reports
  outputs     `batch --html` writes OUT_DIR/STEM.html beside each trajectory and `sweep run --html`
              case-NNNN/view.html in each ok case; the pages open and show the CSV poses
  instanced   300 alike boxes moving and turning: drawn in a few draw calls (one instanced mesh),
              the instance matrices hold the CSV poses, the picture equals the one drawn body by
              body (#inst=0)
  links       (issue 31, item 1) a gallery written outside sweep folders named like a javascript:
              URL, or holding '#', '%', '?': each "view" link is a relative path ('./' first,
              every segment percent-encoded) that opens its case page, and clicking it runs no script
  far         (issue 31, messages) alike boxes 1,000 km out (x = 999999.0123 m) and at 1e300 m: the
              page shows the picture it shows near the origin, and what it draws (the instance
              matrices too) is within 0.1 mm of the CSV 1,000 km out
  names       (issue 31, item 10) JavaScript's own names as keys: #body=constructor, __proto__,
              toString, hasOwnProperty, and CSV bodies named constructor and __proto__: the page
              loads, unknown bodies are ignored, known ones are shown; "1 body, 1 sample"
  artifacts   `batch --golden --junit --artifacts` (issue #29), driven by tests/cli/ci_reports.sh
              as  browser_test.py SIMBOB REPO artifacts WORKDIR ARTDIR JUNIT: ARTDIR/index.html
              links each failed scene's replay page, which shows the golden run as ghosts at its
              rows and the slider's marker at the time the JUnit failure message reports
Chromium must start: a browser that cannot is a failure, never a skip.
"""
import json
import os
import struct
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', 'cli'))
from png_pixels import read_png  # noqa: E402

from selenium import webdriver  # noqa: E402

from chromedriver import LocalService  # noqa: E402

SIMBOB, REPO, CASE, WORK = sys.argv[1:5]
EXTRA = [os.path.abspath(a) for a in sys.argv[5:]]  # the artifacts case's ARTDIR and JUNIT
os.makedirs(WORK, exist_ok=True)
os.chdir(WORK)
failures = []


def fail(msg):
    print('FAIL: ' + msg)
    failures.append(msg)


def run(*args):
    p = subprocess.run([SIMBOB, *args], capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f'simbob {" ".join(args)} exited {p.returncode}: {p.stderr}')
    return p


def browser():
    """Headless Chromium. --no-sandbox: the test runs as root in a container, where Chromium's
    sandbox cannot start; --disable-dev-shm-usage: /dev/shm is small there. WebGL runs on
    SwiftShader (no GPU), which Chromium allows only when asked. Every host name resolves to
    nothing and the proxy is a closed port: nothing leaves the machine."""
    o = webdriver.ChromeOptions()
    for a in ['--headless=new', '--no-sandbox', '--disable-dev-shm-usage', '--use-angle=swiftshader',
              '--enable-unsafe-swiftshader', '--window-size=1000,700', '--host-resolver-rules=MAP * ~NOTFOUND',
              '--proxy-server=127.0.0.1:9', '--disable-background-networking']:
        o.add_argument(a)
    o.set_capability('goog:loggingPrefs', {'browser': 'ALL'})
    d = webdriver.Chrome(service=LocalService(), options=o)
    d.execute_cdp_cmd('Network.enable', {})
    d.execute_cdp_cmd('Network.emulateNetworkConditions',
                      {'offline': True, 'latency': 0, 'downloadThroughput': 0, 'uploadThroughput': 0})
    return d


def open_page(d, path, fragment=''):
    d.get('file://' + os.path.abspath(path) + ('#' + fragment if fragment else ''))
    for _ in range(200):
        if d.execute_script('return !!(window.simbobView && window.simbobView.ready)'):
            break
        time.sleep(0.05)
    else:
        fail(f'{path}: the page never became ready')
    check_console(d, path)
    # Only the page itself and data: URLs were loaded.
    for url in d.execute_script("return performance.getEntriesByType('resource').map(e => e.name)"):
        if not (url.startswith('data:') or url.startswith('file:')):
            fail(f'{path}: the page asked for {url}')


def check_console(d, what):
    for e in d.get_log('browser'):
        if e['level'] == 'SEVERE':
            fail(f'{what}: console error: {e["message"]}')


def seek(d, t, camera=None):
    """Seeks through the URL fragment, as a link would."""
    frag = f't={t}' + (f'&camera={camera}' if camera else '')
    d.execute_script('location.hash = arguments[0]', frag)
    for _ in range(100):
        if abs(d.execute_script('return simbobView.time()') - t) < 1e-9:
            break
        time.sleep(0.02)
    d.execute_script('simbobView.draw()')


def read_csv(path):
    """{time: {body: [7 floats]}} of a trajectory CSV (keys without quotes here)."""
    rows = {}
    with open(path) as f:
        next(f)
        for line in f:
            parts = line.rstrip('\n').split(',')
            rows.setdefault(float(parts[0]), {})[parts[1]] = [float(v) for v in parts[2:9]]
    return rows


def f32(x):
    return struct.unpack('<f', struct.pack('<f', x))[0]


def check_poses(d, csv_rows, times, what, hook='poses'):
    for t in times:
        seek(d, t)
        shown = d.execute_script(f'return simbobView.{hook}()')
        want = csv_rows[t]
        if sorted(shown) != sorted(want):
            fail(f'{what} t={t}: bodies {sorted(shown)} on the page, {sorted(want)} in the CSV')
            continue
        for body, row in want.items():
            got = shown[body]
            exp = [f32(v) for v in row]
            if got != exp:
                fail(f'{what} t={t} {body}: page {got}, CSV as float32 {exp}')


def case_scenes(d):
    scenes = sorted(f for f in os.listdir(os.path.join(REPO, 'scenes')) if f.endswith('.xml'))
    if len(scenes) < 10:
        fail(f'only {len(scenes)} scenes found in scenes/')
    for name in scenes:
        scene = os.path.join(REPO, 'scenes', name)
        base = name[:-4]
        if '<RCLocalSocketCommunicator' in open(scene).read():
            # Needs its peer to run (tests/cli/socket.sh): its golden is a run of it.
            csv = os.path.join(REPO, 'golden', base + '.csv')
        else:
            csv = base + '.csv'
            run('run', scene, '--duration', '0.5', '--sample-interval', '0.05', '--out', csv)
        run('view', csv, '--scene', scene, '-o', base + '.html')
        open_page(d, base + '.html')
        rows = read_csv(csv)
        times = sorted(rows)
        picks = [times[0], times[len(times) // 2], times[-1]]
        check_poses(d, rows, picks, name)
        # A picture of each page at the last time, to look at (docs/images/view.png is one).
        d.execute_script('simbobView.select(arguments[0])', sorted(rows[picks[-1]])[0])
        d.save_screenshot(base + '.png')
        check_console(d, name)
        print(f'ok: {name}: {len(rows[times[0]])} bodies at t = {picks}')


COLOURS = {'RedBox': (0, 'red'), 'GreenBall': (1, 'green'), 'BlueBox': (2, 'blue')}


def centres(path):
    """Centre of the pixels of each pure colour (one channel above 150, the others below 80)."""
    w, h, ch, rows = read_png(path)
    acc = {k: [0, 0, 0] for k in COLOURS}
    for y in range(h):
        line = rows[y]
        for x in range(w):
            px = line[x * ch:x * ch + 3]
            for key, (c, _) in COLOURS.items():
                if px[c] > 150 and all(px[k] < 80 for k in range(3) if k != c):
                    a = acc[key]
                    a[0] += x
                    a[1] += y
                    a[2] += 1
    return {k: (a[0] / a[2], a[1] / a[2], a[2]) if a[2] else None for k, a in acc.items()}


def case_screenshot(d):
    scene = os.path.join(REPO, 'tests', 'data', 'view', 'colors.xml')
    run('run', scene, '--duration', '1', '--out', 'colors.csv')
    run('view', 'colors.csv', '--scene', scene, '-o', 'colors.html')
    open_page(d, 'colors.html')
    # The view at 320x240 CSS pixels (device pixel ratio 1), as `render --size 320x240`.
    d.execute_script("document.body.style.gridTemplateColumns = '320px 300px';"
                     "document.body.style.gridTemplateRows = '240px auto';")
    canvas = d.find_element('css selector', '#view canvas')
    # The tracking camera is pulled along by the body over a recording's frames: seen late first
    # and then earlier, the page must put it where `render --at` does whatever it drew before.
    views = [(c, t) for c in ('Front', 'Spot', 'Rider') for t in (0.0, 0.5, 1.0)] + \
        [('Chase', t) for t in (1.0, 0.3, 0.0, 0.5)]
    for cam, t in views:
        seek(d, t, cam)
        size = d.execute_script('const c = arguments[0]; return [c.width, c.height]', canvas)
        if size != [320, 240]:
            fail(f'canvas is {size}, not 320x240')
        page_png, ref_png = f'page_{cam}_{t}.png', f'render_{cam}_{t}.png'
        canvas.screenshot(page_png)
        run('render', scene, '--at', str(t), '--camera', cam, '--size', '320x240', '--out', ref_png)
        page, ref = centres(page_png), centres(ref_png)
        seen = 0
        for key in COLOURS:
            seen += 1 if page[key] else 0
            if not page[key] and not ref[key]:
                print(f'{cam} t={t} {key}: out of view in both')
                continue
            if not page[key] or not ref[key]:
                fail(f'{cam} t={t} {key}: not seen (page {page[key]}, render {ref[key]})')
                continue
            dx, dy = page[key][0] - ref[key][0], page[key][1] - ref[key][1]
            print(f'{cam} t={t} {key}: page ({page[key][0]:.1f}, {page[key][1]:.1f}) {page[key][2]} px, '
                  f'render ({ref[key][0]:.1f}, {ref[key][1]:.1f}) {ref[key][2]} px')
            if abs(dx) > 3 or abs(dy) > 3:
                fail(f'{cam} t={t} {key}: centre {dx:+.1f}, {dy:+.1f} px away from the render')
        if seen < 2:
            fail(f'{cam} t={t}: fewer than two bodies in view: the view proves little')
    check_console(d, 'colors')


def case_golden(d):
    scene = os.path.join(REPO, 'scenes', 'chain.xml')
    run('run', scene, '--duration', '2', '--out', 'golden.csv')
    # Gravity 1e-6 m/s^2 stronger: the chaotic chain drifts apart and passes the tolerance
    # (1e-6 rad) about half way through (t = 1.19 s on amd64).
    run('run', scene, '--duration', '2', '--out', 'actual.csv', '--set', 'SceneSettings.Gravity=0 -9.810001 0')
    p = subprocess.run([SIMBOB, 'compare', 'actual.csv', 'golden.csv', '--json'],
                       capture_output=True, text=True)
    if p.returncode != 1:
        fail(f'compare exited {p.returncode}, expected 1 (a divergence): {p.stderr}')
    report = json.loads(p.stdout)
    div = report['first_divergence']
    run('view', 'actual.csv', '--scene', scene, '--golden', 'golden.csv', '-o', 'chain.html')
    # `compare --html` writes the same page (exit 1: the comparison failed, the page is written).
    p = subprocess.run([SIMBOB, 'compare', 'actual.csv', 'golden.csv', '--html', 'compare.html', '--scene', scene],
                       capture_output=True, text=True)
    if p.returncode != 1 or open('compare.html', 'rb').read() != open('chain.html', 'rb').read():
        fail(f'compare --html exited {p.returncode} and wrote another page than view --golden: {p.stderr}')
    open_page(d, 'chain.html')
    shown = d.execute_script('return simbobView.divergence()')
    if not shown or shown['time'] != div['time'] or shown['body'] != div['body']:
        fail(f'page divergence {shown}, compare says {div}')
    marker = d.execute_script("const m = document.getElementById('marker');"
                              "return [getComputedStyle(m).display, Number(m.dataset.time)]")
    if marker != ['block', div['time']]:
        fail(f'slider marker {marker}, expected shown at {div["time"]}')
    rows, grows = read_csv('actual.csv'), read_csv('golden.csv')
    times = sorted(rows)
    picks = [times[0], div['time'], times[-1]]
    check_poses(d, rows, picks, 'chain actual')
    check_poses(d, grows, picks, 'chain golden ghosts', hook='goldenPoses')
    # The marker sits on the slider where its thumb stands at the divergence.
    seek(d, div['time'])
    d.execute_script("simbobView.select(arguments[0])", div['body'])
    d.save_screenshot('chain_divergence.png')
    check_console(d, 'chain')
    print(f'ok: divergence at {div["time"]} s ({div["body"]}) marked')


def case_ui(d):
    """The controls: the fragment selects time, camera and body; a click in the view selects the
    body under it; step, play at a speed, loop or stop at the end; trails and shapes switch."""
    scene = os.path.join(REPO, 'tests', 'data', 'view', 'colors.xml')
    run('run', scene, '--duration', '1', '--out', 'colors.csv')
    run('view', 'colors.csv', '--scene', scene, '-o', 'colors.html')
    open_page(d, 'colors.html', 't=0.5&camera=Front&body=GreenBall')
    js = d.execute_script
    got = js('return [simbobView.time(), simbobView.camera(), simbobView.selected()]')
    if got != [0.5, 'Front', 'GreenBall']:
        fail(f'fragment t=0.5&camera=Front&body=GreenBall gave {got}')
    pose_text = js("return document.getElementById('pose').textContent")
    if not pose_text.startswith('GreenBall') or 'position' not in pose_text:
        fail(f'the selected body\'s pose is not shown: {pose_text!r}')
    # Click on the red box where the page draws it (its colour's centre in a screenshot).
    canvas = d.find_element('css selector', '#view canvas')
    canvas.screenshot('ui.png')
    cx, cy, _ = centres('ui.png')['RedBox']
    w, h = js('const r = arguments[0].getBoundingClientRect(); return [r.width, r.height]', canvas)
    from selenium.webdriver.common.action_chains import ActionChains
    ActionChains(d).move_to_element_with_offset(canvas, int(cx - w / 2), int(cy - h / 2)).click().perform()
    if js('return simbobView.selected()') != 'RedBox':
        fail(f'a click on the red box selected {js("return simbobView.selected()")}')
    if 'body=RedBox' not in js('return location.hash'):
        fail(f'the fragment does not follow the selection: {js("return location.hash")}')
    # One sample on.
    s0 = js('return simbobView.sample()')
    d.find_element('id', 'fwd').click()
    if js('return simbobView.sample()') != s0 + 1:
        fail('the step button did not move one sample on')
    # Play at 10x without loop from 0.8 s: reaches the end (1 s) and stops there.
    js("document.getElementById('loop').checked = false;"
       "const sp = document.getElementById('speed'); sp.value = '10'; sp.dispatchEvent(new Event('change'));")
    js('simbobView.seek(0.8); simbobView.play()')
    for _ in range(100):
        if not js('return simbobView.playing()'):
            break
        time.sleep(0.05)
    got = js('return [simbobView.playing(), simbobView.time(), simbobView.frames()]')
    if got[0] or got[1] != 1.0 or got[2] < 1:
        fail(f'play at 10x without loop: [playing, time, frames] = {got}, expected stopped at 1 after frames')
    # With loop: still playing after passing the end, time back near the start at some point.
    js("document.getElementById('loop').checked = true; simbobView.seek(0.9); simbobView.play()")
    seen_wrap = False
    for _ in range(60):
        if js('return simbobView.time()') < 0.5:
            seen_wrap = True
            break
        time.sleep(0.05)
    if not seen_wrap or not js('return simbobView.playing()'):
        fail('play with loop did not wrap around to the start')
    d.find_element('id', 'play').click()
    if js('return simbobView.playing()'):
        fail('the play button did not pause')
    # Trails, every collision shape, the orbit camera following the selection: no console error.
    for box in ('trails', 'geoms', 'follow'):
        d.find_element('id', box).click()
    js("const c = document.getElementById('camera'); c.value = 'orbit'; c.dispatchEvent(new Event('change'));")
    js('simbobView.seek(0.3); simbobView.draw()')
    if js('return simbobView.camera()') != 'orbit':
        fail('the camera list did not switch to the orbit camera')
    d.save_screenshot('ui_orbit.png')
    check_console(d, 'ui')
    print('ok: fragment, click, step, play, loop, pause, trails, shapes, orbit')


def case_gallery(d):
    """`sweep gather --html`: the table with a link to each ok case's page (which opens), failed
    and missing cases marked without a link, sorting by a column, the plot's points."""
    run('sweep', 'plan', os.path.join(REPO, 'scenes', 'sliding_box.sweep.json'), '-o', 'box.jsonl')
    run('sweep', 'run', 'box.jsonl', '-j', '2', '-o', 'box', '-q')
    import shutil
    shutil.rmtree(os.path.join('box', 'case-0003'))  # missing
    with open(os.path.join('box', 'case-0005', 'case.json'), 'w') as f:
        f.write('{"status": "failed", "error": "made to fail by the test"}')
    p = subprocess.run([SIMBOB, 'sweep', 'gather', 'box', '--html', 'box/index.html', '-q'], capture_output=True, text=True)
    if p.returncode != 1:
        fail(f'gather with a missing and a failed case exited {p.returncode}, expected 1: {p.stderr}')
    open_gallery = 'return !!(window.simbobGallery && window.simbobGallery.ready)'
    d.get('file://' + os.path.abspath('box/index.html'))
    if not d.execute_script(open_gallery):
        fail('the gallery did not load')
    check_console(d, 'gallery')
    rows = d.execute_script("""return [...document.querySelectorAll('#table tbody tr')].map(r =>
        [Number(r.dataset.case), r.className, r.querySelector('a') ? r.querySelector('a').href : null])""")
    if len(rows) != 20:
        fail(f'{len(rows)} rows, expected 20')
    for index, cls, href in rows:
        want = 'missing' if index == 3 else 'failed' if index == 5 else 'ok'
        if cls != want or (href is None) != (want != 'ok'):
            fail(f'case {index}: class {cls}, link {href}; expected {want}')
        if href and not os.path.isfile(href[len('file://'):]):
            fail(f'case {index}: the link {href} names no file')
    if d.execute_script('return simbobGallery.points()') != 18:
        fail(f'the plot has {d.execute_script("return simbobGallery.points()")} points, expected the 18 ok cases')
    d.execute_script("simbobGallery.sortBy('stop_x'); simbobGallery.sortBy('stop_x')")  # descending
    order = d.execute_script('return simbobGallery.order()')
    stop = {i: v for i, v in zip(*d.execute_script("""const cols = [...document.querySelectorAll('th')].map(t => t.textContent.replace(/ .$/, ''));
        const k = cols.indexOf('stop_x');
        const rs = [...document.querySelectorAll('#table tbody tr')];
        return [rs.map(r => Number(r.dataset.case)), rs.map(r => r.children[k].textContent)]"""))}
    values = [float(stop[i]) for i in order if stop[i] != '']
    if values != sorted(values, reverse=True):
        fail(f'sorting by stop_x twice did not order it downwards: {values}')
    d.save_screenshot('gallery.png')
    # Follow the first case's link: its replay page opens without an error.
    d.find_element('css selector', '#table tbody tr[data-case="0"] a').click()
    for _ in range(200):
        if d.execute_script('return !!(window.simbobView && window.simbobView.ready)'):
            break
        time.sleep(0.05)
    else:
        fail('the case page behind the link did not open')
    if not d.title.startswith('case 0 Crate.Material.Friction=0.2'):
        fail(f'the case page is titled {d.title!r}')
    check_console(d, 'case page')
    print('ok: gallery rows, links, marks, sorting, plot, a case page')


def case_outputs(d):
    scenes = [os.path.join(REPO, 'scenes', n) for n in ('chain.xml', 'sliding_box.xml')]
    run('batch', *scenes, '--duration', '0.3', '--sample-interval', '0.05', '--out-dir', 'b', '-j', '2', '--html', '-q')
    for stem in ('chain', 'sliding_box'):
        page = os.path.join('b', stem + '.html')
        if not os.path.isfile(page):
            fail(f'batch --html wrote no {page}: {sorted(os.listdir("b"))}')
            continue
        open_page(d, page)
        rows = read_csv(os.path.join('b', stem + '.csv'))
        times = sorted(rows)
        check_poses(d, rows, [times[0], times[-1]], page)
        print(f'ok: {page}')
    run('sweep', 'plan', os.path.join(REPO, 'scenes', 'sliding_box.sweep.json'), '-o', 'box.jsonl')
    run('sweep', 'run', 'box.jsonl', '-j', '2', '-o', 'box', '--html', '-q')
    cases = sorted(c for c in os.listdir('box') if c.startswith('case-'))
    if len(cases) != 20:
        fail(f'{len(cases)} cases, expected 20')
    for c in cases:
        if not os.path.isfile(os.path.join('box', c, 'view.html')):
            fail(f'sweep run --html wrote no {c}/view.html: {sorted(os.listdir(os.path.join("box", c)))}')
    page = os.path.join('box', cases[-1], 'view.html')
    open_page(d, page)
    rows = read_csv(os.path.join('box', cases[-1], 'trajectory.csv'))
    check_poses(d, rows, [sorted(rows)[-1]], page)
    if not d.title.startswith(f'case {int(cases[-1][5:])} '):
        fail(f'{page} is titled {d.title!r}')
    check_console(d, 'outputs')
    print(f'ok: {len(cases)} case pages')


def case_artifacts(d):
    """The failed scenes of a batch's JUnit report, each through the artifacts index to its page."""
    import re
    import xml.etree.ElementTree as ET
    art, junit = EXTRA
    # The golden mismatches: a scene without a golden file is a failure too (issue 45), with no page.
    failed = [c for c in ET.parse(junit).getroot().iter('testcase')
              if c.find('failure') is not None and c.find('failure').get('type') == 'golden mismatch']
    if not failed:
        fail(f'{junit} has no failed test case')
    for case in failed:
        name = case.get('name')
        message = case.find('failure').get('message')
        m = re.match(r"first divergence at t=(\S+) s, body '([^']+)'", message)
        if not m:
            fail(f'{name}: the failure message names no divergence: {message!r}')
            continue
        t, body = float(m.group(1)), m.group(2)
        # From the index, by its link, as a reader would.
        open_page_plain(d, os.path.join(art, 'index.html'))
        links = d.find_elements('css selector', f'a[href="./{name}/view.html"]')
        if len(links) != 1:
            fail(f'index.html has {len(links)} links to ./{name}/view.html')
            continue
        links[0].click()
        wait_ready(d, f'{name}/view.html')
        if not d.current_url.endswith(f'/{name}/view.html'):
            fail(f'the link led to {d.current_url}')
        shown = d.execute_script('return simbobView.divergence()')
        if not shown or shown['time'] != t or shown['body'] != body:
            fail(f'{name}: page divergence {shown}, the JUnit report says t={t} body {body}')
        marker = d.execute_script("const m = document.getElementById('marker');"
                                  "return [getComputedStyle(m).display, Number(m.dataset.time)]")
        if marker != ['block', t]:
            fail(f'{name}: slider marker {marker}, expected shown at {t}')
        if not d.execute_script("return document.getElementById('ghosts').checked"):
            fail(f'{name}: the golden ghosts are not shown')
        # The failure's text names the golden file, relative to where the batch ran (JUNIT's folder).
        g = re.search(r'^golden: (.+)$', case.find('failure').text or '', re.M)
        if not g:
            fail(f'{name}: the failure text names no golden file')
            continue
        golden = read_csv(os.path.join(os.path.dirname(junit), g.group(1)))
        check_poses(d, golden, [t, sorted(golden)[-1]], f'{name} golden ghosts', hook='goldenPoses')
        seek(d, t)
        d.execute_script('simbobView.select(arguments[0])', body)
        d.save_screenshot(os.path.join(WORK, f'{name}_artifact.png'))
        check_console(d, f'{name}/view.html')
        print(f'ok: {name}: ghosts, divergence marked at {t} s ({body})')


def open_page_plain(d, path):
    """A page without the viewer (the artifacts index): loaded, no console error."""
    d.get('file://' + os.path.abspath(path))
    check_console(d, path)


def wait_ready(d, what):
    for _ in range(200):
        if d.execute_script('return !!(window.simbobView && window.simbobView.ready)'):
            return
        time.sleep(0.05)
    fail(f'{what}: the page never became ready')


def case_instanced(d):
    n, samples = 300, 50
    scene = 'boxes.xml'
    subprocess.run([sys.executable, os.path.join(REPO, 'bench', 'gen_scene.py'), str(n), scene], check=True)
    import math
    keys = [f'Box{i}' for i in range(n)]
    with open('boxes.csv', 'w') as f:  # each box circling and turning about its place
        f.write('time,body,x,y,z,qw,qx,qy,qz\n')
        for s in range(samples):
            t = s * 0.02
            for i, key in enumerate(keys):
                a = t * 5 + i * 0.1
                f.write(f'{round(t, 2)!r},{key},{(i % 18) * 0.3 + 0.1 * math.cos(a)!r},{0.101 + 0.05 * math.sin(2 * a)!r},'
                        f'{(i // 18) * 0.3 + 0.1 * math.sin(a)!r},{math.cos(a / 2)!r},0,{math.sin(a / 2)!r},0\n')
    run('view', 'boxes.csv', '--scene', scene, '-o', 'boxes.html')
    rows = read_csv('boxes.csv')
    times = sorted(rows)
    picks = [times[0], times[len(times) // 2], times[-1]]
    pictures = {}
    for frag in ('', 'inst=0'):
        d.get('about:blank')
        open_page(d, 'boxes.html', frag)
        check_poses(d, rows, picks, f'boxes #{frag}')
        calls = d.execute_script('simbobView.draw(); return simbobView.drawCalls()')
        print(f'#{frag}: {calls} draw calls for {n} boxes')
        if frag == '' and calls > 5:
            fail(f'{n} alike boxes take {calls} draw calls: not instanced')
        if frag == 'inst=0' and calls < n:
            fail(f'#inst=0: {calls} draw calls for {n} boxes: still instanced')
        if frag == '':
            if d.execute_script('return simbobView.antialias') is not False:
                fail(f'antialiasing is on with {n} bodies')
            for t in picks:
                seek(d, t)
                shown = d.execute_script('return simbobView.instancedPoses()')
                if sorted(shown) != sorted(rows[t]):
                    fail(f't={t}: instanced bodies {len(shown)}, CSV bodies {len(rows[t])}')
                    continue
                worst = 0
                for body, row in rows[t].items():
                    got = shown[body]
                    sign = 1 if sum(a * b for a, b in zip(got[3:], row[3:])) >= 0 else -1
                    worst = max(worst, max(abs(g - r) for g, r in zip(got[:3], row[:3])),
                                max(abs(sign * g - r) for g, r in zip(got[3:], row[3:])))
                if worst > 1e-5:
                    fail(f't={t}: an instance matrix is {worst} away from its CSV pose')
                print(f'instances at t={t}: at most {worst:.2e} from the CSV poses')
        # The same picture drawn instanced or body by body (the same antialiasing for both).
        d.execute_script("simbobView.seek(arguments[0]); simbobView.draw()", picks[1])
        shot = f'boxes_{frag or "instanced"}.png'
        d.find_element('css selector', '#view canvas').screenshot(shot)
        pictures[frag] = read_png(shot)
    (w, h, ch, a), (_, _, _, b) = pictures[''], pictures['inst=0']
    differ = sum(1 for y in range(h) for x in range(w * ch) if abs(a[y][x] - b[y][x]) > 24) / ch
    # The boxes' orange (the filled shapes' colour, lit): red well above blue; the grey ground not.
    lit = sum(1 for y in range(h) for x in range(0, w * ch, ch) if a[y][x] - a[y][x + 2] > 60)
    print(f'instanced vs body by body: {differ:.0f} of {w * h} pixel values differ, {lit} pixels of boxes')
    if lit < w * h // 50 or differ > w * h // 1000:
        fail(f'the instanced picture differs from the body-by-body one ({differ:.0f} values) or shows too little ({lit})')
    check_console(d, 'instanced')


def tiny_sweep(out):
    """A one-case sweep of sliding_box.xml into the folder `out` (any name), run and gathered."""
    with open('tiny.sweep.json', 'w') as f:
        json.dump({'scene': os.path.join(REPO, 'scenes', 'sliding_box.xml'), 'duration': 0.2, 'sample_interval': 0.05,
                   'vary': [{'param': 'Crate.Material.Friction', 'values': [0.3]}],
                   'metrics': [{'name': 'stop_x', 'body': 'Crate', 'value': 'x', 'stat': 'final'}]}, f)
    run('sweep', 'plan', 'tiny.sweep.json', '-o', 'tiny.jsonl')
    run('sweep', 'run', 'tiny.jsonl', '-j', '1', '-o', out, '-q')


def case_links(d):
    names = ['javascript:self.pwned=7;document.title=%22X%22;void%200%2F%2F', 'hash#x', 'per%41cent', 'what?q=1',
             'sp ace&amp']
    for i, name in enumerate(names):
        tiny_sweep(name)
        gallery = f'gallery{i}.html'
        run('sweep', 'gather', name, '--html', gallery, '-q')
        d.get('file://' + os.path.abspath(gallery))
        if not d.execute_script('return !!(window.simbobGallery && window.simbobGallery.ready)'):
            fail(f'{name}: the gallery did not load')
            continue
        title = d.title
        raw = d.execute_script("const a = document.querySelector('#table tbody a'); return a ? a.getAttribute('href') : null")
        href = d.execute_script("const a = document.querySelector('#table tbody a'); return a ? a.href : null")
        print(f'{name!r}: link {raw!r} -> {href!r}')
        if not raw or not raw.startswith('./'):
            fail(f'{name}: the link {raw!r} does not start with ./')
        if not href or not href.startswith('file://'):
            fail(f'{name}: the link resolves to {href!r}, not a file')
        else:
            from urllib.parse import unquote, urlsplit
            parts = urlsplit(href)
            if parts.query or parts.fragment:
                fail(f'{name}: the link {href!r} has a query or fragment: part of the name was lost')
            want = os.path.abspath(os.path.join(name, 'case-0000', 'view.html'))
            if unquote(parts.path) != want:
                fail(f'{name}: the link names {unquote(parts.path)!r}, the page is {want!r}')
        if not raw:
            continue
        d.find_element('css selector', '#table tbody a').click()
        for _ in range(200):
            if d.execute_script('return !!(window.simbobView && window.simbobView.ready)'):
                break
            time.sleep(0.05)
        else:
            fail(f'{name}: the case page behind the link did not open (at {d.current_url!r}, title {d.title!r})')
        pwned = page_js(d, name, 'return window.pwned === undefined ? null : window.pwned')
        if pwned is not None or d.title == 'X' or d.title == title:
            fail(f'{name}: the click ran script or went nowhere: pwned={pwned}, title {d.title!r}')
        check_console(d, f'{name} case page')
    print('checked: every gallery link opens its case page and runs nothing')


def lit_pixels(path):
    """Pixels of the boxes' orange (the filled shapes' colour, lit): red well above blue."""
    w, h, ch, rows = read_png(path)
    return sum(1 for y in range(h) for x in range(0, w * ch, ch) if rows[y][x] - rows[y][x + 2] > 60)


def case_far(d):
    # Four alike boxes (drawn instanced) and nothing static, lit by a directional light: the same
    # picture wherever the run is (a ground or a point light stays where the scene puts it).
    n = 4
    with open('boxes.xml', 'w') as f:
        f.write('<Simulation><SceneSettings><LightPos Value="1 2 3 0"/></SceneSettings><ComponentList>\n')
        for i in range(n):
            f.write(f'<RCMobileRigidBody Key="Box{i}"><Geom><RCCuboidGeom><Width Value="0.2"/><Height Value="0.2"/>'
                    '<Depth Value="0.2"/></RCCuboidGeom></Geom></RCMobileRigidBody>\n')
        f.write('</ComponentList></Simulation>\n')
    base = {'near': 0.0123, 'far': 999999.0123, 'huge': 1e300}
    shots = {}
    for name, x0 in base.items():
        with open(name + '.csv', 'w') as f:
            f.write('time,body,x,y,z,qw,qx,qy,qz\n')
            for t in (0, 0.5):
                for i in range(n):
                    f.write(f'{t},Box{i},{x0!r},{0.1 + 0.3 * i + t!r},0.25,1,0,0,0\n')
        run('view', name + '.csv', '--scene', 'boxes.xml', '-o', name + '.html')
        d.get('about:blank')
        open_page(d, name + '.html')
        rows = read_csv(name + '.csv')
        for t in (0.0, 0.5):
            seek(d, t)
            for hook in ('poses', 'instancedPoses'):
                shown = page_js(d, name, f'return simbobView.{hook}()') or {}
                for body, row in rows[t].items():
                    got = shown.get(body)
                    if got is None or any(v is None for v in got):  # null: hidden, or NaN / infinite
                        fail(f'{name} t={t} {hook}: {body} is not drawn ({got})')
                        continue
                    err = max(abs(g - r) for g, r in zip(got[:3], row[:3]))
                    if x0 < 1e10 and err > 1e-4:
                        fail(f'{name} t={t} {hook}: {body} at {got[:3]}, {err:.2e} m from the CSV {row[:3]}')
        shot = name + '.png'
        d.find_element('css selector', '#view canvas').screenshot(shot)
        shots[name] = lit_pixels(shot)
        check_console(d, name)
    print(f'lit pixels of the boxes: {shots}')
    if shots['near'] < 500:
        fail(f'the boxes near the origin show {shots["near"]} pixels: the view proves little')
    for name in ('far', 'huge'):
        if abs(shots[name] - shots['near']) > shots['near'] // 10:
            fail(f'{name}: {shots[name]} pixels of boxes, {shots["near"]} near the origin: not the same picture')


def page_js(d, what, script):
    """The value of script on the page, or None and a failure where the page throws (blank page)."""
    try:
        return d.execute_script(script)
    except Exception as e:  # noqa: BLE001 -- a page that throws is what is tested
        fail(f'{what}: {script!r} threw: {str(e).splitlines()[0]}')
        return None


def case_names(d):
    scene = os.path.join(REPO, 'tests', 'data', 'view', 'colors.xml')
    run('run', scene, '--duration', '0.2', '--out', 'colors.csv')
    run('view', 'colors.csv', '--scene', scene, '-o', 'colors.html')
    for frag in ('body=constructor', 'body=__proto__', 'body=toString', 'body=hasOwnProperty', 'body=valueOf&t=0.1',
                 'camera=constructor', 'camera=__proto__'):
        d.get('about:blank')
        open_page(d, 'colors.html', frag)
        if page_js(d, frag, 'return simbobView.selected()') is not None:
            fail(f'#{frag}: a body is selected; an unknown body is ignored')
        if sorted(page_js(d, frag, 'return simbobView.poses()') or {}) != ['BlueBox', 'GreenBall', 'RedBox']:
            fail(f'#{frag}: the page does not show the three bodies')
        print(f'#{frag}: checked')
    # A trajectory whose bodies are named after Object.prototype's properties (none of them in
    # the scene), one sample.
    with open('proto.csv', 'w') as f:
        f.write('time,body,x,y,z,qw,qx,qy,qz\n0,constructor,1,2,3,1,0,0,0\n0,__proto__,4,5,6,1,0,0,0\n'
                '0,toString,7,8,9,1,0,0,0\n')
    run('view', 'proto.csv', '--scene', scene, '-o', 'proto.html')
    want = {'constructor': [1, 2, 3, 1, 0, 0, 0], '__proto__': [4, 5, 6, 1, 0, 0, 0], 'toString': [7, 8, 9, 1, 0, 0, 0]}
    for frag in ('', 'body=constructor', 'body=__proto__'):
        d.get('about:blank')
        open_page(d, 'proto.html', frag)
        # As [key, pose] pairs: WebDriver would turn an own '__proto__' key of an object into a prototype.
        pairs = page_js(d, f'proto.csv #{frag}', 'return Object.entries(simbobView.poses())')
        shown = dict(pairs) if pairs is not None else None
        if shown != want:
            fail(f'proto.csv #{frag}: poses {shown}, expected {want}')
        selected = page_js(d, f'proto.csv #{frag}', 'return simbobView.selected()')
        if frag and selected != frag[5:]:
            fail(f'proto.csv #{frag}: selected {selected}')
    # Counts in words: one body and one sample are singular.
    with open('one.csv', 'w') as f:
        f.write('time,body,x,y,z,qw,qx,qy,qz\n0,RedBox,0,1,0,1,0,0,0\n')
    run('view', 'one.csv', '--scene', scene, '-o', 'one.html')
    for page, end in (('one.html', ' 1 body, 1 sample'), ('colors.html', ' 3 bodies, 21 samples')):
        d.get('about:blank')
        open_page(d, page)
        text = page_js(d, page, "return document.getElementById('scene').textContent") or ''
        if not text.endswith(end):
            fail(f'{page} says {text!r}, expected "...{end}"')
    check_console(d, 'names')
    print('checked: JavaScript names as keys; singular and plural')


def case_meshes(d):
    # scenes/mesh_drop.xml: four meshes, each embedded once and built once as a three.js geometry:
    # the ramp (8 triangles: three quadrilaterals and two ends), the cube and the crate (12 each),
    # the pyramid (6). The ramp is a static triangle mesh, the others' geoms are hulls.
    scene = os.path.join(REPO, 'scenes', 'mesh_drop.xml')
    run('run', scene, '--duration', '1', '--sample-interval', '0.05', '--out', 'mesh_drop.csv')
    run('view', 'mesh_drop.csv', '--scene', scene, '-o', 'mesh_drop.html')
    open_page(d, 'mesh_drop.html')
    rows = read_csv('mesh_drop.csv')
    times = sorted(rows)
    check_poses(d, rows, [times[0], times[-1]], 'mesh_drop')
    built = d.execute_script('return simbobView.meshTriangles()')
    want = {'0:triangles': 8, '1:triangles': 12, '2:triangles': 12, '3:triangles': 6}
    for k, n in want.items():
        if built.get(k) != n:
            fail(f'mesh geometry {k}: {built.get(k)} triangles, expected {n} (built: {built})')
    # The models show in their skins' colours: the jade pyramid, the steel cube, the wooden crate.
    seek(d, 0)
    d.save_screenshot('mesh_drop.png')  # the page, as case_scenes takes it; counted inside the canvas
    r = d.find_element('css selector', '#view canvas').rect
    w, h, ch, px = read_png('mesh_drop.png')
    x0, y0 = int(r['x']), int(r['y'])
    x1, y1 = min(w, x0 + int(r['width'])), min(h, y0 + int(r['height']))
    def count(pred):
        return sum(1 for y in range(y0, y1) for x in range(x0 * ch, x1 * ch, ch)
                   if pred(px[y][x], px[y][x + 1], px[y][x + 2]))
    jade = count(lambda r, g, b: g > r + 40 and g > b + 20)
    steel = count(lambda r, g, b: b > r + 40 and g > r + 10)  # the sky is blue too, but as red as green
    wood = count(lambda r, g, b: r > b + 60 and g > b + 20 and r > g)
    print(f'mesh_drop: {built}; pixels jade {jade}, steel {steel}, wood {wood} of {w * h}')
    for name, n in (('pyramid (jade)', jade), ('cube (steel)', steel), ('crate (wood)', wood)):
        if n < 50:
            fail(f'the {name} is not seen on the page: {n} pixels')
    check_console(d, 'mesh_drop')


def main():
    try:
        d = browser()
    except Exception as e:  # noqa: BLE001 -- any failure to start is the test's failure
        sys.exit(f'FAIL: chromium did not start: {e}')
    try:
        {'scenes': case_scenes, 'screenshot': case_screenshot, 'golden': case_golden, 'ui': case_ui,
         'gallery': case_gallery, 'instanced': case_instanced,
         'outputs': case_outputs, 'links': case_links, 'names': case_names, 'far': case_far,
         'artifacts': case_artifacts, 'meshes': case_meshes}[CASE](d)
    finally:
        d.quit()
    if failures:
        sys.exit(f'{len(failures)} failure(s)')
    print('all ok')


main()
