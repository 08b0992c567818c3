# Command-line cases of the progress bar and the --threads default (exec'd into cli_test.py's
# namespace): a bar on a terminal (stderr on a pseudo-terminal), nothing on a pipe, plain lines
# on a pipe with --progress, never anything on stdout.

import pty
import select


def run_with_terminal_stderr(*args):
    """Runs plmap with stderr on a pseudo-terminal and stdout on a pipe; returns (stdout, the
    bytes written to the terminal, exit code)."""
    master, slave = pty.openpty()
    command = [PLMAP] + [str(a) for a in args]
    process = subprocess.Popen(command, cwd=WORK, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                               stderr=slave)
    os.close(slave)
    terminal = b""
    while True:
        ready, _, _ = select.select([master], [], [], 120)
        if not ready:
            process.kill()
            raise Failure(f"`{' '.join(command)}` hung (no output within 120 s)")
        try:
            chunk = os.read(master, 65536)
        except OSError:  # EIO: the child closed the terminal
            break
        if not chunk:
            break
        terminal += chunk
    stdout = process.stdout.read().decode()
    process.wait(timeout=120)
    os.close(master)
    return stdout, terminal.decode(errors="replace"), process.returncode


def plane_pair():
    run("generate", "grid", "--cells", 30, "-o", "s1.off")
    run("generate", "grid", "--cells", 40, "--jitter", 0.1, "--seed", 2, "-o", "s2.off")
    return "s1.off", "s2.off"


@case
def progress_bar_on_a_terminal():
    s1, s2 = plane_pair()
    out, terminal, code = run_with_terminal_stderr("project", s1, s2, "-o", "p.plmap", "--json")
    expect(code == 0, f"project exited with {code}: {terminal}")
    json.loads(out)  # stdout holds the JSON and nothing else
    expect("S2 edges" in terminal and "%" in terminal, f"no bar on the terminal: {terminal!r}")
    expect("\r" in terminal, f"the bar is not redrawn in place: {terminal!r}")
    expect(terminal.endswith("\r\x1b[K"), f"the bar is not cleared at the end: {terminal[-80:]!r}")
    # the bar of a command that only reads a map
    out, terminal, code = run_with_terminal_stderr("info", "p.plmap", "--json", "--no-quality")
    expect(code == 0 and "reading map" in terminal, f"info shows no progress while reading: {terminal!r}")
    # --no-progress: nothing, even on a terminal
    _, terminal, code = run_with_terminal_stderr("project", s1, s2, "-o", "q.plmap", "--json", "--no-progress")
    expect(code == 0 and terminal == "", f"--no-progress still drew: {terminal!r}")


@case
def no_progress_on_a_pipe_unless_asked():
    s1, s2 = plane_pair()
    out, err, _ = run("project", s1, s2, "-o", "p.plmap", "--json")
    json.loads(out)
    expect(err == "", f"progress on a pipe without --progress: {err!r}")
    out, err, _ = run("project", s1, s2, "-o", "p.plmap", "--json", "--progress")
    json.loads(out)
    expect("\r" not in err and "\x1b" not in err, f"--progress on a pipe must write plain lines: {err!r}")
    lines = err.splitlines()
    for phase in ("rays from S1 vertices", "S2 edges", "finalize", "writing map"):
        expect(any(line.startswith(phase + ": 100%") for line in lines), f"no line for the end of {phase}: {lines}")
    out, err, _ = run("smooth", "p.plmap", "-o", "s.plmap", "--json", "--progress")
    expect(any(line.startswith("reading map:") for line in err.splitlines()), f"smooth: {err!r}")
    expect(any(line.startswith("smoothing sweeps: 100%") for line in err.splitlines()), f"smooth: {err!r}")
    expect_clean_error(["project", s1, s2, "-o", "p.plmap", "--progress", "--no-progress"], code=64,
                       mention="--progress")


@case
def simplify_progress_and_threads_default():
    run("generate", "delaunay", "--points", 150, "--lift", "--seed", 11, "-o", "hill.off")
    out, err, _ = run("simplify", "hill.off", "-o", "c.plmap", "--target-elements", 60, "--json", "--progress")
    j = json.loads(out)
    expect(j["threads"] == os.cpu_count(), f"simplify: threads {j['threads']}, cores {os.cpu_count()}")
    lines = err.splitlines()
    expect(any(line.startswith("removing vertices: 100%") for line in lines), f"simplify: {lines}")
    expect(any(line.startswith("finalize: 100%") for line in lines), f"simplify: {lines}")
    out, _, _ = run("simplify", "--help")
    expect("all hardware threads" in out, f"simplify --help should say what 0 threads means: {out}")
