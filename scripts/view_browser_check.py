"""The real-browser check of `tessera view` (run by scripts/view_browser_check.sh): headless
Chromium opens the page, waits for the image, checks it shows the scene, orbits with a mouse drag,
changes a material colour, and saves a screenshot. Each step prints what it measured; any failed
check exits non-zero."""
import sys
import time

from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.action_chains import ActionChains

url, profile, screenshot = sys.argv[1], sys.argv[2], sys.argv[3]

opts = webdriver.ChromeOptions()
opts.binary_location = "/usr/bin/chromium"
for flag in ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
             "--disable-background-networking", "--disable-component-update", "--disable-sync",
             f"--user-data-dir={profile}", "--window-size=1000,620"]:
    opts.add_argument(flag)
driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=opts)

# Mean codes of the canvas and of its 16x16-pixel blocks: block means average the noise away, so
# two frames of one view agree closely and a changed view shows.
STATS = """const c = document.getElementById('view');
const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
const B = 16, bw = Math.ceil(c.width / B), bh = Math.ceil(c.height / B);
const blocks = new Array(bw * bh * 3).fill(0), counts = new Array(bw * bh).fill(0);
let s = [0, 0, 0], s2 = 0, n = 0;
for (let y = 0; y < c.height; y++) for (let x = 0; x < c.width; x++) {
  const i = 4 * (y * c.width + x), b = Math.floor(y / B) * bw + Math.floor(x / B);
  for (let k = 0; k < 3; k++) { s[k] += d[i + k]; s2 += d[i + k] * d[i + k]; blocks[3 * b + k] += d[i + k]; }
  counts[b]++; n++;
}
const m = (s[0] + s[1] + s[2]) / (3 * n);
return {shown: c.dataset.shown || '', mean: m, std: Math.sqrt(s2 / (3 * n) - m * m),
        rgb: s.map(x => x / n), blocks: blocks.map((v, j) => v / counts[Math.floor(j / 3)])};"""

SHOWN = "return document.getElementById('view').dataset.shown || '';"


def wait(what, cond, timeout=60):
    t0 = time.time()
    while time.time() - t0 < timeout:
        v = cond()
        if v:
            return v
        time.sleep(0.1)
    print(f"FAIL: timed out waiting for {what}")
    driver.quit()
    sys.exit(1)


def check(ok, msg):
    print(("ok:   " if ok else "FAIL: ") + msg)
    if not ok:
        driver.quit()
        sys.exit(1)


def shown_generation_spp():
    """(generation, spp) of the frame the canvas shows, from its key generation/spp/preview/exposure."""
    k = driver.execute_script(SHOWN).split("/")
    return (int(k[0]), int(k[1]), k[2] == "true") if len(k) == 4 else (0, 0, False)


def diff(a, b):
    """Mean absolute difference of the block means, in 8-bit codes."""
    return sum(abs(x - y) for x, y in zip(a["blocks"], b["blocks"])) / len(a["blocks"])


driver.get(url)
g, spp, _ = wait("the first full frame", lambda: (lambda t: t if t[1] >= 4 else None)(shown_generation_spp()))
first = driver.execute_script(STATS)
print(f"first frame: generation {g}, {spp} spp shown, mean code {first['mean']:.1f}, std {first['std']:.1f}")
check(first["mean"] > 20 and first["std"] > 10, "the canvas shows the scene (not blank, not flat)")
# Control for the orbit check below: the same view at more samples differs by little.
wait("the same view at 4 times the samples", lambda: (lambda t: t if t[0] == g and t[1] >= 4 * spp else None)(shown_generation_spp()))
same = driver.execute_script(STATS)
print(f"same view at {shown_generation_spp()[1]} spp: block difference {diff(first, same):.2f} codes")
check(diff(first, same) < 2, "two frames of one view agree (control)")

canvas = driver.find_element("id", "view")
ActionChains(driver).move_to_element(canvas).click_and_hold().move_by_offset(12, 0) \
    .move_by_offset(12, 6).release().perform()
g2, spp2, _ = wait("a frame of the orbited view",
                   lambda: (lambda t: t if t[0] > g and t[1] >= 4 else None)(shown_generation_spp()))
orbited = driver.execute_script(STATS)
state = driver.execute_script("return fetch('/api/state').then(r => r.json())")
print(f"after the drag: generation {g2}, camera origin {[round(c, 3) for c in state['camera']['origin']]}, "
      f"block difference {diff(same, orbited):.2f} codes")
check(diff(same, orbited) > 4, "orbiting changed the image")

# The floor of the Cornell box (BSDF #1) turned blue through its colour picker.
driver.execute_script("""const i = document.querySelector('input[data-bsdf="1"][data-param="reflectance"]');
i.value = '#1030ff'; i.dispatchEvent(new Event('change'));""")
g3, spp3, _ = wait("a frame of the blue floor",
                   lambda: (lambda t: t if t[0] > g2 and t[1] >= 4 else None)(shown_generation_spp()))
blue = driver.execute_script(STATS)
state = driver.execute_script("return fetch('/api/state').then(r => r.json())")
floor = state["bsdfs"][1]["params"][0]["value"]
print(f"after the colour edit: generation {g3}, floor reflectance {floor}, "
      f"mean RGB {[round(c, 1) for c in orbited['rgb']]} -> {[round(c, 1) for c in blue['rgb']]}")
check(blue["rgb"][2] - blue["rgb"][0] > orbited["rgb"][2] - orbited["rgb"][0] + 3,
      "the image turned bluer")
check(abs(floor[2] - 1.0) < 1e-6 and floor[0] < 0.01, "the state holds the edited colour")

wait("32 spp for the screenshot", lambda: shown_generation_spp()[1] >= 32)
driver.save_screenshot(screenshot)
print(f"screenshot: {screenshot}")
driver.quit()
print("browser check passed")
