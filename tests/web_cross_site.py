# A page on another origin in a real browser (Debian's Chromium, headless, driven by chromedriver through
# selenium), for tests/web/web_cross_site.rs. Arguments: DAEMON_PORT EVIL_PORT. `evil.example` resolves to 127.0.0.1
# (a host-resolver rule); this script serves the other site's page on EVIL_PORT. The page tries to open the bay
# screen's WebSocket by every name (127.0.0.1, localhost, evil.example: the rebound name) and send the probe's
# controls (club `sw`, exclude shot 1, player "pwned"), and to read the session CSV; then the browser opens the
# screen's own address under the attacker's name (DNS rebinding) and, last, the screen from its own origin.
# Prints RESULT {...}. Exit 2 without a browser.
import http.server, json, shutil, sys, threading, time

daemon_port, evil_port = sys.argv[1], int(sys.argv[2])
chromium = shutil.which("chromium") or shutil.which("chromium-browser")
driver_exe = shutil.which("chromedriver")
if not chromium or not driver_exe:
    print("no browser: this test needs Debian's chromium and chromium-driver (bash scripts/test.sh installs them)", file=sys.stderr)
    sys.exit(2)

EVIL = """<!doctype html><meta charset="utf-8"><title>evil</title><script>
const D = "%s";
const CONTROLS = [{op: "club", rig: "bay1", club: "sw"}, {op: "exclude", rig: "bay1", shot: 1, excluded: true},
                  {op: "labels", rig: "bay1", player: "pwned", tags: []}];
window.__attacks = {};
function attempt(name, url) {
  return new Promise((done) => {
    let ws;
    try { ws = new WebSocket(url); } catch (e) { window.__attacks[name] = "threw " + e; return done(); }
    const t = setTimeout(() => { if (!window.__attacks[name]) window.__attacks[name] = "no answer"; done(); }, 5000);
    ws.onopen = () => {
      window.__attacks[name] = "open";
      for (const c of CONTROLS) ws.send(JSON.stringify(c));
      setTimeout(() => { ws.close(); clearTimeout(t); done(); }, 500);
    };
    ws.onclose = () => { if (!window.__attacks[name]) window.__attacks[name] = "refused"; clearTimeout(t); done(); };
  });
}
(async () => {
  await attempt("loopback", `ws://127.0.0.1:${D}/ws`);
  await attempt("localhost", `ws://localhost:${D}/ws`);
  await attempt("rebound", `ws://evil.example:${D}/ws`);
  try {
    const r = await fetch(`http://127.0.0.1:${D}/rig/bay1/session.csv`);
    window.__attacks.csv = "read " + (await r.text()).length + " bytes";
  } catch (e) { window.__attacks.csv = "blocked"; }
  window.__done = true;
})();
</script>""" % daemon_port


class Evil(http.server.BaseHTTPRequestHandler):
    def do_GET(self):
        body = EVIL.encode()
        self.send_response(200)
        self.send_header("Content-Type", "text/html; charset=utf-8")
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        self.wfile.write(body)

    def log_message(self, *args):
        pass


server = http.server.ThreadingHTTPServer(("127.0.0.1", evil_port), Evil)
threading.Thread(target=server.serve_forever, daemon=True).start()

from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By

options = webdriver.ChromeOptions()
options.binary_location = chromium
for a in ["--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--no-proxy-server",
          "--host-resolver-rules=MAP evil.example 127.0.0.1", "--disable-background-networking", "--no-first-run"]:
    options.add_argument(a)
driver = webdriver.Chrome(service=Service(executable_path=driver_exe), options=options)
js = driver.execute_script


def wait(what, cond, limit=30.0):
    t0 = time.time()
    while time.time() - t0 < limit:
        v = cond()
        if v:
            return v
        time.sleep(0.05)
    raise SystemExit(f"timed out waiting for {what}")


try:
    driver.get(f"http://evil.example:{evil_port}/")
    wait("the other site's attempts", lambda: js("return window.__done === true"))
    attacks = js("return window.__attacks")
    # DNS rebinding: the bay screen's own port under the attacker's name.
    driver.get(f"http://evil.example:{daemon_port}/")
    rebound_page = driver.find_element(By.TAG_NAME, "body").text
    driver.get(f"http://evil.example:{daemon_port}/rig/bay1/session.csv")
    rebound_csv = driver.find_element(By.TAG_NAME, "body").text
    # The screen from its own origin still connects and may control.
    driver.get(f"http://127.0.0.1:{daemon_port}/")
    wait("the screen's own page", lambda: js("return window.bay && bay.connected && bay.rigs.length > 0"))
    own = js("return {connected: bay.connected, controls: bay.controls}")
    print("RESULT " + json.dumps({"attacks": attacks, "rebound_page": rebound_page, "rebound_csv": rebound_csv, "own": own}), flush=True)
finally:
    driver.quit()
    server.shutdown()
