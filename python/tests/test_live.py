"""`Model.live`: the server `elastokin live` starts, started from Python on a copy of the shipped
MacPherson, asked over real HTTP (urllib) as a browser asks it. Its figures against `Model.run` of the
same file, and of the file edited by hand after an edit through HTTP; who is refused; the notebook's
frame; and a stop, or the end of a `with` block, leaving the port free."""

import json
import shutil
import socket
import urllib.error
import urllib.request
from pathlib import Path

import pytest

import elastokin

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "macpherson.json"
TIE_ROD_INNER_Z = "/suspension/macpherson/hardpoints/tie_rod_inner/2"
STEPS = 8


@pytest.fixture
def copy(tmp_path):
    """A copy of the shipped MacPherson, which a save may write."""
    path = tmp_path / "macpherson.json"
    shutil.copy(EXAMPLE, path)
    return path


def ask(url, body=None, headers=None):
    """The status and JSON body of a request to ``url`` (a POST when there is a ``body``)."""
    data = None if body is None else json.dumps(body).encode()
    request = urllib.request.Request(url, data=data, headers=headers or {}, method="GET" if body is None else "POST")
    try:
        with urllib.request.urlopen(request, timeout=60) as answer:
            return answer.status, json.loads(answer.read())
    except urllib.error.HTTPError as refused:
        return refused.code, json.loads(refused.read())


def figures(state, analysis="parallel-travel"):
    """Every figure of ``analysis`` in a state, by key: its SI value."""
    entry = next(a for a in state["analyses"] if a["name"] == analysis)
    return {f["key"]: f["value"] for f in entry["figures"] if "value" in f}


def same_to_the_bit(live, run):
    """The live state's SI figures against a run's, every one the run has a value of."""
    ran = {key: f["si_value"] for key, f in run.summary["figures"].items() if f.get("si_value") is not None}
    assert len(ran) >= 5 and set(ran) <= set(live)
    for key, value in ran.items():
        # The same file, read and run the same way: the same bits.
        assert live[key] == value, f"{key}: live {live[key]!r}, run {value!r}"


def refused_to_connect(port):
    """Whether nothing listens at ``port`` on this machine."""
    try:
        socket.create_connection(("127.0.0.1", port), timeout=5).close()
        return False
    except OSError:
        return True


def test_the_served_figures_are_the_runs_and_an_edit_is_the_file_edited_by_hand(copy, tmp_path):
    model = elastokin.load(copy)
    server = model.live("parallel-travel", steps=STEPS)
    try:
        assert server.url.startswith(f"http://127.0.0.1:{server.port}/") and server.url.endswith("/")
        status, first = ask(server.url + "state")
        assert status == 200, first
        same_to_the_bit(figures(first["state"]), model.run("parallel-travel", steps=STEPS))

        status, edited = ask(server.url + "edit", {"pointer": TIE_ROD_INNER_Z, "value": -0.0394})
        assert status == 200, edited
        assert edited["state"]["version"] == 2
        original = copy.read_text()
        by_hand = original.replace("[-0.150, 0.370, -0.0374]", "[-0.150, 0.370, -0.0394]", 1)
        assert by_hand != original
        hand = tmp_path / "by_hand.json"
        hand.write_text(by_hand)
        run = elastokin.load(hand).run("parallel-travel", steps=STEPS)
        same_to_the_bit(figures(edited["state"]), run)
        assert abs(figures(edited["state"])["bump_steer"] - figures(first["state"])["bump_steer"]) > 1e-3
        # The edit answers without the error estimates; asked for, they are the run's, to the bit.
        assert edited["state"]["estimated"] is False
        status, rested = ask(server.url + "estimate", {"version": 2})
        assert status == 200, rested
        errors = {f["key"]: f["error"] for f in rested["analyses"][0]["figures"]}
        ran = {key: f["si_error"] for key, f in run.summary["figures"].items() if f.get("si_error") is not None}
        assert len(ran) >= 5
        for key, error in ran.items():
            assert errors[key] == error, f"{key}: live {errors[key]!r}, run {error!r}"
        assert copy.read_text() == original, "nothing saved unless asked"
    finally:
        unsaved = server.stop()
    assert unsaved is True, "the edit was not saved, and the stop says so"
    assert server.stop() is False, "stopped already"


def test_a_request_without_the_token_or_from_another_page_is_refused(copy):
    with elastokin.load(copy).live("parallel-travel", steps=STEPS, frame_ancestors=()) as server:
        root = f"http://127.0.0.1:{server.port}/"
        status, body = ask(root + "state")
        assert status == 403 and "token" in body["error"]
        status, body = ask(root + "0" * 32 + "/state")
        assert status == 403
        edit = {"pointer": TIE_ROD_INNER_Z, "value": -0.0394}
        status, body = ask(server.url + "edit", edit, {"Origin": "http://evil.example"})
        assert status == 403 and "another page" in body["error"]
        # The notebook's page is another origin too: it may frame the page, never drive the server.
        status, body = ask(server.url + "edit", edit, {"Origin": "http://localhost:8888"})
        assert status == 403
        status, body = ask(server.url + "state")
        assert status == 200 and body["state"]["version"] == 1 and body["state"]["moved"] == []


def test_the_page_shows_in_a_notebook_frame_that_the_server_allows(copy):
    model = elastokin.load(copy)
    with model.live("parallel-travel", steps=STEPS) as server:
        shown = server._repr_html_()
        assert shown.startswith("<iframe") and f'src="{server.url}"' in shown
        with urllib.request.urlopen(server.url, timeout=60) as page:
            assert page.status == 200 and "text/html" in page.headers["Content-Type"]
            policy = page.headers["Content-Security-Policy"]
            assert policy == "frame-ancestors 'self' http://localhost:* http://127.0.0.1:*"
            assert page.headers["X-Frame-Options"] is None
            assert page.headers["Connection"] == "close"
        assert repr(server) == f"<elastokin.LiveServer {model.name!r}: {server.url}>"
    assert "is stopped" in server._repr_html_() and "stopped>" in repr(server)
    # The command's framing: the page's own origin alone.
    with model.live("parallel-travel", steps=STEPS, frame_ancestors=()) as server:
        with urllib.request.urlopen(server.url, timeout=60) as page:
            assert page.headers["Content-Security-Policy"] == "frame-ancestors 'self'"
            assert page.headers["X-Frame-Options"] == "SAMEORIGIN"


def test_a_stop_and_the_end_of_a_with_block_leave_the_port_free(copy):
    model = elastokin.load(copy)
    server = model.live("parallel-travel", steps=STEPS)
    port, url = server.port, server.url
    assert ask(url + "state")[0] == 200 and server.serving
    assert server.stop() is False, "nothing was edited"
    assert not server.serving and refused_to_connect(port)
    with pytest.raises(urllib.error.URLError):
        urllib.request.urlopen(url + "state", timeout=10)
    with socket.socket() as again:
        # As a server binds (Rust's standard library too): a connection of the port's past closing on this
        # machine does not hold it; a socket still listening would.
        again.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        again.bind(("127.0.0.1", port))
        again.listen()

    with model.live("parallel-travel", steps=STEPS, port=port) as server:
        assert server.port == port and ask(server.url + "state")[0] == 200
    assert refused_to_connect(port)


def test_what_cannot_be_served_says_what_to_do(copy):
    with pytest.raises(elastokin.ModelError, match=r"not read from a file.*elastokin.load\(path\).live\(\)"):
        elastokin.load(json.loads(copy.read_text())).live()
    model = elastokin.load(copy)
    with pytest.raises(ValueError, match="no analysis 'travel'"):
        model.live("travel")
    with pytest.raises(ValueError, match="bind 'here': give an IP address"):
        model.live("parallel-travel", bind="here")
    with pytest.raises(ValueError, match=r"frame ancestor '\*': .*http://localhost:\*"):
        model.live("parallel-travel", frame_ancestors=["*"])
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        with pytest.raises(OSError, match=f"cannot listen on 127.0.0.1 port {port}.*choose another port="):
            model.live("parallel-travel", steps=STEPS, port=port)
    copy.unlink()
    with pytest.raises(elastokin.ModelError, match="macpherson.json"):
        model.live("parallel-travel")


def test_every_design_is_judged_against_the_targets_given(copy):
    targets = ROOT / "examples" / "targets" / "macpherson.json"
    with elastokin.load(copy).live("parallel-travel", steps=STEPS, targets=str(targets)) as server:
        status, body = ask(server.url + "state")
        assert status == 200
        judged = [(t["figure"], t["met"]) for t in body["state"]["targets"]]
        assert judged == [("bump_steer", True), ("wheel_rate", True)], "the shipped example meets its targets"
