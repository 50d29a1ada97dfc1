-- expect: safe_os_execute\.lua:5: os\.execute\(\): not available with --safe \(it runs a program\)
-- case: permission | --safe: a deck runs a shell command with os.execute
-- options: --safe
-- status: 1
os.execute("touch '" .. mpm.outdir .. "/ran'")
error("os.execute was not refused")
