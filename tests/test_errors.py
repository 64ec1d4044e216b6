"""Error lines echo what a user gave (keys, file names, paths) with no raw control
character: one function, ga_rotors.errors.echoed, serves scene errors and paths."""

from __future__ import annotations

import unicodedata

from hypothesis import given
from hypothesis import strategies as st

from ga_rotors.cli import main
from ga_rotors.errors import ECHO_LIMIT, SceneError, echoed
from ga_rotors.files import SHOWN_CHARS, shown_path

TITLE = "\x1b]0;owned\x07"  # retitles a terminal that receives it raw


def _raw_controls(text: str) -> list[str]:
    return [c for c in text if unicodedata.category(c)[0] == "C"]


@given(st.text(), st.text(), st.text())
def test_a_scene_error_line_carries_no_control_character(file, key, detail):
    message = str(SceneError(file, key, detail))
    assert _raw_controls(message) == []
    for part in (key, detail):  # as it is (escaped) unless a word of it is too long
        if all(len(word) <= ECHO_LIMIT for word in echoed(part).split()):
            assert echoed(part) in message


@given(st.text(max_size=300))
def test_a_path_is_echoed_escaped_and_short(path):
    shown = shown_path(path)
    assert _raw_controls(shown) == []
    assert shown == echoed(path, SHOWN_CHARS)
    if len(echoed(path)) > SHOWN_CHARS:
        assert len(shown) < SHOWN_CHARS + 30


def test_escapes_and_bidirectional_overrides_show_as_escapes():
    assert echoed(f"top{TITLE}\n\r\t\u202e\x7f") == "top\\x1b]0;owned\\x07\\n\\r\\t\\u202e\\x7f"
    assert echoed("ω = (0, 0, 1) rad/s, θ") == "ω = (0, 0, 1) rad/s, θ"  # text stays text


def test_a_key_with_a_terminal_escape_is_one_escaped_line(tmp_path, capsys):
    # Before, only \r and \n were escaped: ESC ] 0; ... BEL reached the terminal raw.
    scene = tmp_path / f"s{TITLE}.toml"
    scene.write_text(
        '[body]\nmoments = [1.0, 2.0, 3.0]\n"\\u001b]0;owned\\u0007" = 1\n[time]\nduration = 1.0\n',
        encoding="utf-8",
    )
    assert main(["run", str(scene), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and _raw_controls(err.rstrip("\n")) == []
    assert "s\\x1b]0;owned\\x07.toml: body.\\x1b]0;owned\\x07: unknown key" in err


def test_a_long_word_is_cut_in_its_middle():
    word = "k" * 1000 + "END"
    message = str(SceneError("s.toml", word, "unknown key"))
    assert len(message) < 150 and "END (1003 characters)" in message
