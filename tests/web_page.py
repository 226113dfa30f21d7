# The bay screen in a real browser (Debian's Chromium, headless, driven by chromedriver through selenium), for
# tests/web/web_page.rs. Arguments: URL RIG SHOTS OUT_DIR. Lines on stdout: READY {...} once the page is up, DONE
# {...} after the checks, then (after RESTARTED on stdin) RECONNECTED {...}. Exit 2 without a browser.
import json, os, shutil, sys, time

url, rig, shots, out_dir = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
chromium = shutil.which("chromium") or shutil.which("chromium-browser")
driver_exe = shutil.which("chromedriver")
if not chromium or not driver_exe:
    print("no browser: this test needs Debian's chromium and chromium-driver (bash scripts/test.sh installs them)", file=sys.stderr)
    sys.exit(2)

from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By

downloads = os.path.join(out_dir, "downloads")
shutil.rmtree(downloads, ignore_errors=True)
os.makedirs(downloads)
options = webdriver.ChromeOptions()
options.binary_location = chromium
for a in ["--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--no-proxy-server",
          "--window-size=1600,1000", "--disable-background-networking", "--no-first-run"]:
    options.add_argument(a)
options.add_experimental_option("prefs", {"download.default_directory": downloads, "download.prompt_for_download": False})
driver = webdriver.Chrome(service=Service(executable_path=driver_exe), options=options)
js = driver.execute_script


def wait(what, cond, limit=30.0):
    # The page redraws its tables as messages arrive: an element read mid-redraw is stale, not an answer.
    from selenium.common.exceptions import NoSuchElementException, StaleElementReferenceException
    t0 = time.time()
    while time.time() - t0 < limit:
        try:
            v = cond()
        except (StaleElementReferenceException, NoSuchElementException):
            v = None
        if v:
            return v
        time.sleep(0.02)
    raise SystemExit(f"timed out waiting for {what}")


def retry(action, limit=5.0):
    """Runs `action` again when the element it found was redrawn under it (stale) or is not drawn yet."""
    from selenium.common.exceptions import NoSuchElementException, StaleElementReferenceException
    t0 = time.time()
    while True:
        try:
            return action()
        except (StaleElementReferenceException, NoSuchElementException):
            if time.time() - t0 > limit:
                raise
            time.sleep(0.02)


def emit(tag, value):
    print(tag, json.dumps(value), flush=True)


try:
    # The browser's own start (its first renderer) is not the page's load: open an empty page first.
    driver.get("about:blank")
    driver.get(url)
    wait("the first snapshot", lambda: js("return window.bay && bay.connected && bay.firstDrawMs !== null"))
    nav = js("const n = performance.getEntriesByType('navigation')[0]; return {load: n.loadEventEnd, dom: n.domContentLoadedEventEnd, request: n.requestStart, response: n.responseEnd, resources: performance.getEntriesByType('resource').map(r => [r.name, r.startTime, r.responseEnd])};")
    # Every (shot, ball speed) the shot view shows, as it changes.
    js("""window.__seen = []; new MutationObserver(() => {
            const s = document.getElementById('shot-number').textContent;
            const v = document.getElementById('v-ball_speed').textContent;
            const last = window.__seen[window.__seen.length - 1];
            if (!last || last[0] !== s || last[1] !== v) window.__seen.push([s, v]);
          }).observe(document.getElementById('headline'), {subtree: true, childList: true, characterData: true});""")
    emit("READY", {"load_ms": nav["load"], "dom_ms": nav["dom"], "first_draw_ms": js("return bay.firstDrawMs"), "timing": nav})

    wait("the shots", lambda: js(f"return bay.data['{rig}'].shots.length >= {shots}"), 120)
    wait("the last shot's comparison", lambda: js(f"const c = bay.data['{rig}'].comparisons; return c.length && c[c.length - 1].shot === {shots}"), 10)
    time.sleep(0.3)
    seen = js("return window.__seen")
    comparison = js("return [...document.querySelectorAll('#cmp-rows tr')].map(r => [...r.cells].map(c => c.textContent))")
    comparison_shot = driver.find_element(By.ID, "cmp-shot").text
    unit = driver.find_element(By.ID, "u-ball_speed").text
    shot_sigma = driver.find_element(By.ID, "s-ball_speed").text
    driver.save_screenshot(os.path.join(out_dir, "shot-view.png"))

    # The club control: the page puts the text on golf/<rig>/club.
    club_before = driver.find_element(By.ID, "rig-club").text
    driver.find_element(By.ID, "club").send_keys("iron7")
    driver.find_element(By.ID, "club-set").click()
    # The rig's status names its club now (the switch is loaded off the sample path, then shows in the next status).
    rig_club = wait("the new club in the rig's status", lambda: (lambda t: t if t.startswith("iron7") else None)(driver.find_element(By.ID, "rig-club").text), 10)
    # Player and tags for the next shots.
    driver.find_element(By.ID, "player").send_keys("ann")
    driver.find_element(By.ID, "tags").send_keys("fitting, shaft A")
    driver.find_element(By.ID, "labels-set").click()
    wait("the labels back from the bus", lambda: "ann" in driver.find_element(By.ID, "labels-now").text)

    # The session view: the table's ball speeds, a mishit excluded with a click, the CSV downloaded.
    driver.find_element(By.CSS_SELECTOR, "#views button[data-view=session]").click()
    read_table = "return [...document.querySelectorAll('#shots tbody tr')].map(r => [...r.cells].map(c => c.textContent))"
    rows = wait("the shot table", lambda: js(read_table))
    # A cell is its value, then its one sigma where the shot carries one (`162.8 ± 2.1`).
    table = {r[0]: r[2].split(" ± ")[0] for r in rows}
    table_sigma = {r[0]: r[2].split(" ± ")[1] if " ± " in r[2] else None for r in rows}
    retry(lambda: driver.find_element(By.CSS_SELECTOR, "#shots button[data-exclude='2']").click())
    wait("shot 2 excluded", lambda: "excluded" in driver.find_element(By.CSS_SELECTOR, "#shots tr[data-shot='2']").get_attribute("class"))
    summary_shots = retry(lambda: driver.find_element(By.CSS_SELECTOR, "#summary tbody tr td:nth-child(2)").text)
    # Grouped by player and by tag (as `impactd session --by`): each group's name and shots counted.
    read_summary = "return [...document.querySelectorAll('#summary tbody tr')].map(r => [r.cells[0].textContent, r.cells[1].textContent])"
    by = {}
    for group in ["player", "tag"]:
        driver.find_element(By.CSS_SELECTOR, f"#group-by option[value={group}]").click()
        wait(f"the summary per {group}", lambda: driver.find_element(By.ID, "group-name").text == group)
        by[group] = dict(wait(f"the rows per {group}", lambda: js(read_summary)))
        if group == "player":
            driver.save_screenshot(os.path.join(out_dir, "session-by-player.png"))
    driver.find_element(By.CSS_SELECTOR, "#group-by option[value=club]").click()
    # Sorting by ball speed (descending, then ascending on a second click).
    sort_header = lambda: driver.find_element(By.CSS_SELECTOR, "#shots th[data-sort=ball_speed]").click()
    retry(sort_header)
    down = [float(r[2].split(" ± ")[0]) for r in js(read_table)]
    driver.save_screenshot(os.path.join(out_dir, "session-view.png"))
    driver.find_element(By.ID, "csv").click()
    csv_path = os.path.join(downloads, f"{rig}-session.csv")
    wait("the CSV download", lambda: os.path.exists(csv_path) and not os.path.exists(csv_path + ".crdownload"))

    # Units through the bus and back: metric, then imperial again.
    driver.find_element(By.CSS_SELECTOR, "#views button[data-view=shot]").click()
    driver.find_element(By.CSS_SELECTOR, "#units option[value=metric]").click()
    wait("metric units", lambda: driver.find_element(By.ID, "u-ball_speed").text == "m/s")
    metric_speed = driver.find_element(By.ID, "v-ball_speed").text
    driver.save_screenshot(os.path.join(out_dir, "shot-view-metric.png"))
    driver.find_element(By.CSS_SELECTOR, "#units option[value=imperial]").click()
    wait("imperial units", lambda: driver.find_element(By.ID, "u-ball_speed").text == "mph")

    emit("DONE", {
        "seen": seen, "unit": unit, "comparison": comparison, "comparison_shot": comparison_shot, "table": table, "table_sigma": table_sigma, "shot_sigma": shot_sigma, "summary_shots": summary_shots, "by": by, "club_before": club_before, "rig_club": rig_club, "sorted_down": down,
        "csv": csv_path, "metric_speed": metric_speed, "latencies_ms": js("return bay.latencies"),
    })

    # The daemon restarts: the page reconnects by itself and shows the new daemon's (empty) session.
    line = sys.stdin.readline()
    assert line.strip() == "RESTARTED", line
    wait("the page to notice", lambda: js(f"return bay.data['{rig}'].shots.length === 0 && bay.connected"), 30)
    connection = driver.find_element(By.ID, "connection").text
    # A day at the bay in one go: 1500 shots (with flights) and 200 comparisons through the page's own message
    # handler; what the page keeps stays within its bounds.
    js(f"""
        const rig = '{rig}', line = [[0, 0, 0], [50, 10, 1], [100, 0, 2]];
        for (let i = 0; i < 1500; i++) {{
          onMessage({{type: 'shot', rig, shot: 10000 + i, published_ns: Date.now() * 1e6, club: 'driver',
                     club_file: 'driver', labels: {{}}, warnings: [], m: {{ball_speed_mph: 150}}, flight: line}});
          if (i % 7 === 0) onMessage({{type: 'comparison', rig, comparison: {{shot: 10000 + i, device: 'LM',
                     predicted: {{}}, measured: {{}}, residual: {{}}}}}});
        }}""")
    time.sleep(0.5)  # the drawn times are taken in the next animation frame
    kept = js(f"""
        const d = bay.data['{rig}'];
        return {{shots: d.shots.length, flights: d.flights.length, comparisons: d.comparisons.length,
                latencies: bay.latencies.length, rows: document.querySelectorAll('#shots tbody tr').length}};""")
    emit("RECONNECTED", {"connection": connection, "kept": kept})
finally:
    driver.quit()
