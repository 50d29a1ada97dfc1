#!/usr/bin/python3
"""moraine: the run log OUTDIR/log.txt, the end-of-run summary, the thermo
columns and the progress bar.

  check_run_log.py MORAINE WORKDIR

Runs small decks that end well, fail, are interrupted by SIGINT, are stopped
by the watchdog, call os.exit(), run quietly or run two simulations (of one
name), and checks that
  - log.txt holds everything printed (moraine's messages, the thermo lines,
    the deck's print, io.write, io.stdout:write and io.stderr:write), in order;
  - the summary (screen and log) gives the status, the steps, the simulated
    time, the wall time, the particle-steps per second, the time per phase,
    the peak memory and the files written (count equal to the files there);
  - thermo columns picked by name print those columns, with the values of
    diagnostics.csv;
  - a log that cannot be written (a symbolic link) stops the run with exit
    status 3 and writes nothing through the link;
  - on a terminal (a pseudo-terminal here) the progress bar stays on its own
    line around the thermo lines, shows the ETA as h:mm:ss and is not drawn
    at 100 % after an interrupt; with no terminal there is no bar.
"""
import csv
import os
import pty
import re
import shutil
import subprocess
import sys

MORAINE, WORK = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
problems = []

HEAD = """
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = { 1, 0.5 }, cell = 0.05 }, gravity = { 0, -9.81 },
  name = "block", thermo = %s, diagnostics_every = 10, output = { vtk = "part", every_steps = 20 } }
sim:add_particles(mpm.box{ min = { 0.1, 0.0 }, max = { 0.3, 0.2 } }, { material = mat })
"""

DECKS = {
    "ok": HEAD % "10" + """
print("print:", 1, 2.5, true)
io.write("io.write: ", 3, " ", 0.5, "\\n")
io.stdout:write("io.stdout:write\\n")
io.stderr:write("io.stderr:write\\n")
sim:run{ steps = 40 }
print("after the run")
""",
    "failed": HEAD % "10" + """
sim:run{ steps = 20 }
error("the deck gives up")
""",
    "interrupted": HEAD % "10" + """
sim:hook{ every_steps = 1, fn = function(s)
  if s:step() == 25 then io.popen("kill -INT $PPID"):close() end
end }
sim:run{ steps = 100 }
""",
    "columns": HEAD % ('{ every = 10, columns = { "step", "time", "E_kinetic", "W_plastic", "W_MPM", "particles",'
                       ' "steps_per_s" } }') + """
sim:run{ steps = 30 }
sim:run{ steps = 10, thermo = { columns = { "step", "com_y" } } }
sim:run{ steps = 10, thermo = 5 }
""",
    "two": HEAD % "0" + """
-- of the same name, but another simulation: a line of its own
local other = mpm.simulation{ dim = 2, grid = { size = { 1, 0.5 }, cell = 0.05 }, name = "block", thermo = 0,
  diagnostics = false, series = false }
other:add_particles(mpm.box{ min = { 0.5, 0.0 }, max = { 0.6, 0.1 } }, { material = mat })
sim:run{ steps = 10 }
other:run{ steps = 7 }
sim:run{ steps = 5 }
""",
}


def check(cond, what):
    if not cond:
        problems.append(what)
    return cond


def run(name, deck_text, *options, env=None):
    out = os.path.join(WORK, name)
    shutil.rmtree(out, ignore_errors=True)
    deck = os.path.join(WORK, name + ".lua")
    with open(deck, "w") as f:
        f.write(deck_text)
    proc = subprocess.run([MORAINE, deck, "-o", out, *options], capture_output=True, text=True, timeout=300, env=env)
    log_path = os.path.join(out, "log.txt")
    log = open(log_path).read() if os.path.exists(log_path) else ""
    check(log, f"{name}: no log.txt")
    return proc, log, out


def in_order(lines, log, what):
    """every line of `lines` is a line of the log, in the same order"""
    rest = log.split("\n")
    for line in lines:
        if line not in rest:
            return check(False, f"{what}: line {line!r} not in the log (in order)")
        rest = rest[rest.index(line) + 1:]
    return True


def summary(text):
    """{field: value} of the summary in text (the last one)"""
    fields = {}
    part = text.rsplit("\nsummary:\n", 1)
    if not check(len(part) == 2, "no summary"):
        return fields
    for line in part[1].split("\n"):
        m = re.match(r"  (\S+(?: \S+)*?)\s{2,}(.*)", line)
        if m:
            key = m.group(1)
            fields.setdefault(key, []).append(m.group(2))
    return {k: v if k == "simulation" else v[0] for k, v in fields.items()}


def size_bytes(text):
    value, unit = text.split()
    return float(value) * {"B": 1, "kB": 1e3, "MB": 1e6, "GB": 1e9}[unit]


def check_summary(name, s, status, out):
    check(re.match(status, s.get("status", "")), f"{name}: status {s.get('status')!r} !~ /{status}/")
    check(re.match(r"\d+:\d\d:\d\d \([0-9.e+-]+ s\), [0-9.e+-]+ particle-steps/s$", s.get("wall time", "")),
          f"{name}: wall time {s.get('wall time')!r}")
    check(re.match(r"[0-9.]+ [kMG]?B$", s.get("peak memory", "")), f"{name}: peak memory {s.get('peak memory')!r}")
    phases = s.get("time per phase", "")
    check(all(f"{p} " in phases for p in ("p2g", "grid", "g2p", "stress", "sort", "other")),
          f"{name}: time per phase {phases!r}")
    m = re.match(r"(\d+), (.*) \(besides the log\)$", s.get("files written", ""))
    if check(m, f"{name}: files written {s.get('files written')!r}"):
        files = [os.path.join(r, f) for r, _, fs in os.walk(out) for f in fs if f != "log.txt"]
        total = sum(os.path.getsize(f) for f in files)
        check(int(m.group(1)) == len(files), f"{name}: {m.group(1)} files written, {len(files)} there")
        got = size_bytes(m.group(2))
        check(abs(got - total) <= 0.06 * total + 1, f"{name}: {m.group(2)} written, {total} bytes there")


def case_ok():
    proc, log, out = run("ok", DECKS["ok"])
    check(proc.returncode == 0, f"ok: exit status {proc.returncode}: {proc.stderr}")
    check(log.startswith("moraine ") and MORAINE in log.split("\n")[0], "ok: the log's first line")
    in_order([l for l in proc.stdout.split("\n") if l], log, "ok stdout")
    in_order([l for l in proc.stderr.split("\n") if l], log, "ok stderr")
    in_order(["print:\t1\t2.5\ttrue", "io.write: 3 0.5", "io.stdout:write", "io.stderr:write"], log, "ok prints")
    check(re.search(r"\n +step +time .*\n +0 .*\n +10 ", log), "ok: thermo lines in the log")
    s = summary(log)
    check_summary("ok", s, r"ok \(exit status 0\)$", out)
    check(s.get("simulation") == ["'block': 40 steps (0 -> 40), t = 0 -> 0.00316228 s, 64 particles"],
          f"ok: simulation {s.get('simulation')}")
    check(summary(proc.stderr) == s, "ok: the summary on the screen differs from the log's")


def case_failed():
    proc, log, out = run("failed", DECKS["failed"])
    check(proc.returncode == 1, f"failed: exit status {proc.returncode}")
    check(re.search(r"\nmoraine: .*failed\.lua:8: the deck gives up\n", log), "failed: the error is not in the log")
    s = summary(log)
    check_summary("failed", s, r"failed \(exit status 1\): .*failed\.lua:8: the deck gives up$", out)
    check(s.get("simulation", [""])[0].startswith("'block': 20 steps"), f"failed: {s.get('simulation')}")


def case_interrupted():
    proc, log, out = run("interrupted", DECKS["interrupted"])
    check(proc.returncode == 130, f"interrupted: exit status {proc.returncode}")
    s = summary(log)
    check_summary("interrupted", s,
                  r"interrupted \(exit status 130\): .*run\{\}: interrupted by signal 2 after step 25", out)
    check(s.get("simulation", [""])[0].startswith("'block': 25 steps (0 -> 25)"), f"interrupted: {s.get('simulation')}")


def case_watchdog():
    deck = open(os.path.join(os.path.dirname(__file__), "..", "bad", "watchdog_speed.lua")).read()
    proc, log, out = run("watchdog", deck)
    check(proc.returncode == 1, f"watchdog: exit status {proc.returncode}")
    check_summary("watchdog", summary(log), r"stopped by the watchdog \(exit status 1\): .*the watchdog stopped", out)


def case_quiet():
    proc, log, out = run("quiet", DECKS["ok"], "-q")
    check(proc.returncode == 0, f"quiet: exit status {proc.returncode}")
    check(" step " not in proc.stdout and "summary:" not in proc.stderr, "quiet: thermo or summary on the screen")
    check(re.search(r"\n +step +time ", log) and "\nsummary:\n" in log, "quiet: thermo or summary missing in the log")
    check("print:\t1" in proc.stdout, "quiet: the deck's print is not on the screen")


def case_columns():
    proc, log, out = run("columns", DECKS["columns"])
    check(proc.returncode == 0, f"columns: exit status {proc.returncode}: {proc.stderr}")
    lines = proc.stdout.split("\n")
    headers = [l.split() for l in lines if l.strip().startswith("step")]
    want = [["step", "time", "E_kinetic", "W_plastic", "W_MPM", "particles", "steps_per_s"], ["step", "com_y"],
            ["step", "time", "E_kinetic", "W_plastic", "W_MPM", "particles", "steps_per_s"]]
    check(headers == want, f"columns: headers {headers}")
    rows = {int(r["step"]): r for r in csv.DictReader(open(os.path.join(out, "diagnostics.csv")))}
    current = None
    compared = 0
    for l in lines:
        cells = l.split()
        if cells and cells[0] == "step":
            current = cells
        elif cells and current and int(cells[0]) in rows:
            row = rows[int(cells[0])]
            for name, value in zip(current, cells):
                if name in row:
                    check(abs(float(value) - float(row[name])) <= 1e-6 * abs(float(row[name])) + 1e-300,
                          f"columns: step {cells[0]} {name} = {value}, CSV {row[name]}")
                    compared += 1
    check(compared >= 20, f"columns: only {compared} values compared with the CSV")
    check([l for l in lines if re.match(r" +\d+ ", l)][-1].split()[0] == "50", "columns: the last line is not step 50")


def case_two():
    proc, log, out = run("two", DECKS["two"])
    check(proc.returncode == 0, f"two: exit status {proc.returncode}")
    sims = summary(log).get("simulation", [])
    check(len(sims) == 2 and sims[0].startswith("'block': 15 steps (0 -> 15)") and
          sims[1].startswith("'block': 7 steps (0 -> 7)"), f"two: {sims}")


def case_os_exit():
    # true: the Lua state is closed first, so the sanitizers have no leak to report
    proc, log, out = run("os_exit", HEAD % "10" + "sim:run{ steps = 10 }\nos.exit(4, true)\n")
    check(proc.returncode == 4, f"os_exit: exit status {proc.returncode}")
    s = summary(log)
    check(s.get("status") == "ended by os.exit() in the deck", f"os_exit: status {s.get('status')!r}")
    check(s.get("simulation", [""])[0].startswith("'block': 10 steps"), f"os_exit: {s.get('simulation')}")


def case_no_outdir():
    """without -o the log goes where every output goes: ./out"""
    cwd = os.path.join(WORK, "cwd")
    shutil.rmtree(cwd, ignore_errors=True)
    os.makedirs(cwd)
    proc = subprocess.run([MORAINE, os.path.join(WORK, "ok.lua"), "-q"], cwd=cwd, capture_output=True, text=True,
                          timeout=300)
    check(proc.returncode == 0, f"no_outdir: exit status {proc.returncode}")
    log = os.path.join(cwd, "out", "log.txt")
    check(os.path.exists(log) and "\nsummary:\n" in open(log).read(), "no_outdir: no out/log.txt with a summary")


def case_unwritable_log():
    out = os.path.join(WORK, "link")
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    target = os.path.join(WORK, "link_target.txt")
    open(target, "w").write("untouched\n")
    os.symlink(target, os.path.join(out, "log.txt"))
    deck = os.path.join(WORK, "ok.lua")
    proc = subprocess.run([MORAINE, deck, "-o", out], capture_output=True, text=True, timeout=300)
    check(proc.returncode == 3, f"link: exit status {proc.returncode}")
    check(re.search(r"moraine: cannot write '.*link/log\.txt': Too many levels of symbolic links", proc.stderr),
          f"link: message {proc.stderr!r}")
    check(open(target).read() == "untouched\n", "link: the log was written through a symbolic link")
    check(not os.path.exists(os.path.join(out, "part.pvd")), "link: the deck ran without its log")


def terminal_run(name, deck_text):
    """the bytes moraine writes on a pseudo-terminal (stdout and stderr)"""
    out = os.path.join(WORK, name)
    shutil.rmtree(out, ignore_errors=True)
    deck = os.path.join(WORK, name + ".lua")
    open(deck, "w").write(deck_text)
    master, slave = pty.openpty()
    proc = subprocess.Popen([MORAINE, deck, "-o", out], stdin=slave, stdout=slave, stderr=slave)
    os.close(slave)
    data = b""
    while True:
        try:
            chunk = os.read(master, 4096)
        except OSError:
            break
        if not chunk:
            break
        data += chunk
    os.close(master)
    return proc.wait(timeout=300), data.decode(errors="replace")


def screen_lines(data):
    """the lines a terminal shows: \\r, \\n and erase-to-end-of-line interpreted"""
    lines, col, i = [""], 0, 0
    while i < len(data):
        if data.startswith("\033[K", i):
            lines[-1] = lines[-1][:col]
            i += 3
            continue
        c = data[i]
        if c == "\r":
            col = 0
        elif c == "\n":
            lines.append("")
            col = 0
        else:
            lines[-1] = lines[-1][:col] + c + lines[-1][col + 1:]
            col += 1
        i += 1
    return [l for l in lines if l]


SLOW = """
sim:hook{ every_steps = 1, fn = function()  -- 20 ms a step: the bar is drawn (every 0.25 s)
  local t = mpm.wall_time()
  while mpm.wall_time() - t < 0.02 do end
end }
"""
BAR = re.compile(r"^\[[#.]{30}\] +\d+\.\d%  ETA \d+:\d\d:\d\d$")


def case_terminal():
    try:
        for fd in os.openpty():
            os.close(fd)
    except OSError as e:  # a container without /dev/ptmx: the checks without a terminal still run
        print(f"no pseudo-terminal ({e}): the bar on a terminal is not checked")
        return case_no_terminal()
    status, data = terminal_run("tty", HEAD % "10" + SLOW + "sim:run{ steps = 60 }\n")
    check(status == 0, f"tty: exit status {status}")
    lines = screen_lines(data)
    thermo = [l for l in lines if re.match(r" +\d+ +\d\.\d{6}e[+-]\d\d ", l)]
    check(len(thermo) == 7, f"tty: {len(thermo)} whole thermo lines on the screen, expected 7: {lines}")
    check(data.count("\r\033[K") >= 3, "tty: the bar was not cleared around the thermo lines")
    bars = [l for l in lines if l.startswith("[")]
    check(bars and all(BAR.match(b) for b in bars) and bars[-1].split("]")[1].split()[0] == "100.0%",
          f"tty: the bar lines {bars}")
    status, data = terminal_run("tty_interrupted", HEAD % "10" + SLOW + """
sim:hook{ every_steps = 1, fn = function(s)
  if s:step() == 30 then io.popen("kill -INT $PPID"):close() end
end }
sim:run{ steps = 60 }
""")
    check(status == 130, f"tty_interrupted: exit status {status}")
    check("100.0%" not in data, "tty_interrupted: the bar was drawn at 100 % after the interrupt")
    check(re.search(r"\[[#.]{30}\]", data), "tty_interrupted: no bar drawn before the interrupt")
    check(not any(l.startswith("[") for l in screen_lines(data)), "tty_interrupted: a bar is left on the screen")
    case_no_terminal()


def case_no_terminal():
    """no terminal: no bar and no control characters"""
    proc, log, out = run("notty", HEAD % "10" + SLOW + "sim:run{ steps = 20 }\n")
    check("\r" not in proc.stderr + proc.stdout and "\033" not in proc.stderr + proc.stdout, "notty: a bar was drawn")
    check("\033" not in log and "\r" not in log, "the log holds control characters")


def main():
    os.makedirs(WORK, exist_ok=True)
    for case in (case_ok, case_failed, case_interrupted, case_watchdog, case_quiet, case_columns, case_two,
                 case_os_exit, case_no_outdir, case_unwritable_log, case_terminal):
        before = len(problems)
        case()
        print(("ok   " if len(problems) == before else "FAIL ") + case.__name__[5:])
    for p in problems:
        print("FAIL:", p)
    print(f"{len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
