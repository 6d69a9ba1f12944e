#!/usr/bin/env python3
"""Peak resident memory (VmHWM) of petra-fsw against ROI size, both matchers.

Boots petra-fsw with the flight default configuration (no "budget" section but
the camera's frame size; --roi-budget: budget.roi_width/roi_height = the ROI,
so the arena is sized for it), then for each ROI size and matcher: SET_PARAM
MATCH_METHOD, SELECT_ROI centred on the simulated rock, EVALUATE; reads the
acknowledgements and the process's VmHWM (/proc/PID/status) after each run.
One petra-fsw per (size, matcher), so each VmHWM is that run's own peak.
Writes a CSV and an SVG plot; prints a Markdown table. --breakdown also prints, for
each run, what is resident after EVALUATE (/proc/PID/smaps, Rss): every anonymous
mapping of 256 KiB or more, the heap, the stacks, and each library's file mappings.

  python3 tests/bench/fsw_memory.py --build build/release --roi-budget \
      --out docs/img/fsw_memory.svg --csv /tmp/fsw_memory.csv
"""
import argparse
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

SIZES = [(256, 192), (320, 240), (384, 288), (448, 336), (512, 384)]
METHODS = [(0, "dp"), (1, "graph cut")]


def vm_kb(pid, field):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith(field + ":"):
                return int(line.split()[1])
    return 0


def rss_breakdown(pid):
    """[(what, rss_kb)] from /proc/PID/smaps, largest first: each anonymous mapping of
    256 KiB or more by its size, the rest of the anonymous ones, [heap], [stack], and
    the file mappings summed per file."""
    parts, name, size_kb = {}, None, 0
    with open("/proc/%d/smaps" % pid) as f:
        for line in f:
            head = line.split()
            if "-" in head[0] and not head[0].endswith(":"):  # a mapping's first line
                path = head[5] if len(head) > 5 else ""
                name = os.path.basename(path) if path.startswith("/") else (path or "anon")
            elif head[0] == "Size:":
                size_kb = int(head[1])
            elif head[0] == "Rss:" and int(head[1]) > 0:
                rss = int(head[1])
                key = name
                if name == "anon":
                    key = "anon mapping of %.1f MiB" % (size_kb / 1024) if rss >= 256 else "anon, small"
                parts[key] = parts.get(key, 0) + rss
    return sorted(parts.items(), key=lambda kv: -kv[1])


def free_port():
    import socket
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.bind(("127.0.0.1", 0))
    p = s.getsockname()[1]
    s.close()
    return p


class Fsw:
    def __init__(self, petra, fsw, work, width, height, config_extra):
        self.petra, self.work = petra, work
        self.cmd_port, self.tlm_port = free_port(), free_port()
        cfg = {"uplink": {"host": "127.0.0.1", "port": self.cmd_port, "key_file": "petra.key"},
               "downlink": {"host": "127.0.0.1", "port": self.tlm_port},
               "budget": {"image_width": width, "image_height": height},
               "camera": {"kind": "file", "dir": "pairs"}, "calib": "calib.json"}
        cfg["budget"].update(config_extra)
        with open(os.path.join(work, "fsw.json"), "w") as f:
            json.dump(cfg, f)
        self.log = open(os.path.join(work, "fsw.log"), "w")
        self.proc = subprocess.Popen([fsw, "--config", os.path.join(work, "fsw.json")],
                                     stdout=self.log, stderr=subprocess.STDOUT)
        time.sleep(0.5)
        self.boot_hwm_kb = 0

    def cmd(self, *words, timeout_ms=120000):
        r = subprocess.run([self.petra, "cmd", *words, "--key", os.path.join(self.work, "petra.key"),
                            "--port", str(self.cmd_port), "--wait", "--tlm-port",
                            str(self.tlm_port), "--timeout-ms", str(timeout_ms)],
                           capture_output=True, text=True)
        return r.stdout.strip().splitlines()[-1] if r.stdout.strip() else r.stderr.strip()

    def wait_boot(self):
        for _ in range(600):  # until NOOP is answered: boot done
            if self.proc.poll() is not None:
                return False
            if "COMPLETED" in self.cmd("NOOP", timeout_ms=500):
                self.boot_hwm_kb = vm_kb(self.proc.pid, "VmHWM")
                return True
        return False

    def stop(self):
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)
            self.proc.wait(timeout=30)
        self.log.close()


def run_one(a, work, width, height, truth, w, h, method):
    extra = dict(a.config_extra)
    if a.roi_budget:  # the budget sized for this ROI: VmHWM against the ROI budget
        extra.update({"roi_width": w, "roi_height": h})
    fsw = Fsw(a.petra, a.fsw, work, width, height, extra)
    try:
        if not fsw.wait_boot():
            return {"error": "no boot: " + open(os.path.join(work, "fsw.log")).read().strip()}
        rx, ry, rw, rh = truth["roi"]  # [x, y, w, h]
        cx, cy = rx + rw // 2, ry + rh // 2
        x = min(max(cx - w // 2, 0), width - w)
        y = min(max(cy - h // 2, 0), height - h)
        fsw.cmd("SET_PARAM", "param_id=2", "value=%d" % method)  # MATCH_METHOD
        sel = fsw.cmd("SELECT_ROI", "x_px=%d" % x, "y_px=%d" % y, "w_px=%d" % w, "h_px=%d" % h,
                      "planes=%d" % truth.get("planes", 2))
        ev = fsw.cmd("EVALUATE", "acquire=1", timeout_ms=600000) if "COMPLETED" in sel else ""
        if a.breakdown:
            print("  resident after EVALUATE, %dx%d: %s" % (w, h, ", ".join(
                "%s %.1f" % (k, v / 1024) for k, v in rss_breakdown(fsw.proc.pid) if v >= 128)),
                file=sys.stderr)
        return {"select": sel, "evaluate": ev, "boot_kb": fsw.boot_hwm_kb,
                "hwm_kb": vm_kb(fsw.proc.pid, "VmHWM")}
    finally:
        fsw.stop()


def svg(rows, path, limit_mib):
    W, H, L, B = 640, 400, 70, 50
    xs = [r["pixels"] for r in rows]
    xmax = max(xs) * 1.05
    ymax = max([limit_mib * 1.1] + [r["hwm_mib"] * 1.1 for r in rows if r["hwm_mib"]])
    X = lambda v: L + v / xmax * (W - L - 20)
    Y = lambda v: H - B - v / ymax * (H - B - 20)
    s = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" '
         'font-size="12"><rect width="100%%" height="100%%" fill="white"/>' % (W, H)]
    s.append('<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="black"/>' % (L, H - B, W - 20, H - B))
    s.append('<line x1="%d" y1="%d" x2="%d" y2="20" stroke="black"/>' % (L, H - B, L))
    for k in range(0, int(ymax) + 1, 16):
        s.append('<text x="%d" y="%.0f" text-anchor="end">%d</text>' % (L - 6, Y(k) + 4, k))
    for r in rows:
        if r["method"] == "dp":
            s.append('<text x="%.0f" y="%d" text-anchor="middle">%dx%d</text>' %
                     (X(r["pixels"]), H - B + 16, r["w"], r["h"]))
    s.append('<text x="%d" y="%d" text-anchor="middle">ROI (px)</text>' % ((W + L) // 2, H - 10))
    s.append('<text x="16" y="%d" transform="rotate(-90 16 %d)" text-anchor="middle">'
             'peak resident memory VmHWM (MiB)</text>' % (H // 2, H // 2))
    s.append('<line x1="%d" y1="%.0f" x2="%d" y2="%.0f" stroke="gray" stroke-dasharray="6,4"/>'
             % (L, Y(limit_mib), W - 20, Y(limit_mib)))
    s.append('<text x="%d" y="%.0f" text-anchor="end" fill="gray">target %d MiB</text>' %
             (W - 24, Y(limit_mib) - 4, limit_mib))
    for (m, name), colour in zip(METHODS, ["#1f77b4", "#d62728"]):
        pts = [(X(r["pixels"]), Y(r["hwm_mib"])) for r in rows if r["method"] == name and r["ok"]]
        if pts:
            s.append('<polyline fill="none" stroke="%s" stroke-width="2" points="%s"/>' %
                     (colour, " ".join("%.0f,%.0f" % p for p in pts)))
            for p in pts:
                s.append('<circle cx="%.0f" cy="%.0f" r="3" fill="%s"/>' % (p[0], p[1], colour))
        yl = 36 + 16 * m
        s.append('<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="%s" stroke-width="2"/>' %
                 (L + 20, yl - 4, L + 44, yl - 4, colour))
        s.append('<text x="%d" y="%d">%s</text>' % (L + 50, yl, name))
    s.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(s) + "\n")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--build", default="build/release")
    p.add_argument("--out", help="SVG plot to write")
    p.add_argument("--csv", help="CSV to write")
    p.add_argument("--sizes", help="WxH,WxH,... (default: 128x96 .. 512x384)")
    p.add_argument("--arena-mb", type=float, help="budget.arena_mb (default: none, the flight default)")
    p.add_argument("--seed", type=int, default=3)
    p.add_argument("--roi-budget", action="store_true",
                   help="budget.roi_width/roi_height = each ROI (default: the flight default budget)")
    p.add_argument("--fsw", help="petra-fsw binary (default: BUILD/fsw/petra-fsw)")
    p.add_argument("--breakdown", action="store_true",
                   help="print what is resident after each EVALUATE (MiB, on stderr)")
    a = p.parse_args()
    a.petra = os.path.join(a.build, "sim/petra")
    a.fsw = a.fsw or os.path.join(a.build, "fsw/petra-fsw")
    a.config_extra = {"arena_mb": a.arena_mb} if a.arena_mb else {}
    sizes = [tuple(int(v) for v in s.split("x")) for s in a.sizes.split(",")] if a.sizes else SIZES
    work = tempfile.mkdtemp(prefix="petra_fsw_memory_")
    try:
        subprocess.run([a.petra, "sim", "scene", "--seed", str(a.seed), "--out",
                        os.path.join(work, "scene")], check=True, capture_output=True)
        os.makedirs(os.path.join(work, "pairs"))
        for side in ("left", "right"):
            shutil.copy(os.path.join(work, "scene/%s.pgm" % side),
                        os.path.join(work, "pairs/%s.pgm" % side))
        with open(os.path.join(work, "pairs/left.pgm"), "rb") as f:
            f.readline()
            width, height = (int(v) for v in f.readline().split())
        shutil.copy(os.path.join(work, "scene/calib.json"), os.path.join(work, "calib.json"))
        subprocess.run([a.petra, "keygen", "--out", os.path.join(work, "petra.key")], check=True,
                       capture_output=True)
        truth = json.load(open(os.path.join(work, "scene/truth.json")))
        rows = []
        print("| ROI (px) | matcher | SELECT_ROI | EVALUATE | VmHWM after boot (MiB) | VmHWM after EVALUATE (MiB) |")
        print("|---|---|---|---|---|---|")
        for w, h in sizes:
            for m, name in METHODS:
                r = run_one(a, work, width, height, truth, w, h, m)
                ok = "COMPLETED" in r.get("evaluate", "")
                row = {"w": w, "h": h, "pixels": w * h, "method": name, "ok": ok,
                       "hwm_mib": r.get("hwm_kb", 0) / 1024.0, "boot_mib": r.get("boot_kb", 0) / 1024.0}
                rows.append(row)
                state = lambda line: next((s for s in ("COMPLETED", "REJECTED", "FAILED")
                                           if s in line), line[:80] or "-")
                print("| %dx%d | %s | %s | %s | %.1f | %.1f |" %
                      (w, h, name, state(r.get("select", r.get("error", ""))),
                       state(r.get("evaluate", "")), row["boot_mib"], row["hwm_mib"]))
                if not ok:
                    print("  ", r, file=sys.stderr)
                sys.stdout.flush()
        if a.csv:
            with open(a.csv, "w") as f:
                f.write("w,h,method,completed,boot_vmhwm_mib,vmhwm_mib\n")
                for r in rows:
                    f.write("%d,%d,%s,%d,%.2f,%.2f\n" % (r["w"], r["h"], r["method"], r["ok"],
                                                         r["boot_mib"], r["hwm_mib"]))
        if a.out:
            svg(rows, a.out, 64)
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
