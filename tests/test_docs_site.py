"""The built documentation site, opened in a headless browser: its pages load and so do their figures.

``.ci/run`` builds the site (``sphinx-build -W --keep-going -b html docs docs/_build/html``) before the
tests. This opens the home page and a tutorial page in headless Chromium (the system's ``chromium`` and
``chromium-driver`` packages, driven by selenium) and checks that every ``<img>`` has loaded
(``complete`` and ``naturalWidth > 0``), that MathJax typesets the equations, that the tutorial shows its
figures, and that every internal link of the site resolves (``docs/check_links.py``). The theory pages
must show their equations typeset, with no ``$`` left as text and no MathJax error; the API pages must
give whole sentences as summaries (not cut at "Eqs.") in tables no wider than the page. Outside CI, a
missing browser or an unbuilt site skips the test and says what to install or run; in CI (``CI=true``)
both fail it.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest
from scripts import load_script

ROOT = Path(__file__).resolve().parent.parent
SITE = ROOT / "docs" / "_build" / "html"
DRIVER = "/usr/bin/chromedriver"
BUILD = "pip install -e '.[docs]' && sphinx-build -W --keep-going -b html docs docs/_build/html"
INSTALL = "apt-get update && apt-get install -y chromium chromium-driver"
TUTORIAL = "tutorials/01-quickstart.html"
#: A folder to keep the screenshots in (``MOVING_BOGIE_SCREENSHOTS=DIR``), to look at them.
SHOTS = Path(os.environ["MOVING_BOGIE_SCREENSHOTS"]) if os.environ.get("MOVING_BOGIE_SCREENSHOTS") else None


def _missing(reason: str) -> None:
    if os.environ.get("CI") == "true":
        pytest.fail(f"{reason} (required in CI)", pytrace=False)
    pytest.skip(reason)


def _chromium() -> str:
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return ""


@pytest.fixture(scope="module")
def browser():
    if not (SITE / "index.html").is_file():
        _missing(f"the documentation site is not built: {BUILD}")
    binary = _chromium()
    if not binary or not Path(DRIVER).is_file():
        _missing(f"headless Chromium and its driver are not installed: {INSTALL}")
    try:
        from selenium import webdriver
        from selenium.webdriver.chrome.service import Service
    except ImportError:
        _missing("selenium is not installed: pip install -e '.[docs]'")
    options = webdriver.ChromeOptions()
    options.binary_location = binary
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1280,1600"):
        options.add_argument(flag)
    driver = webdriver.Chrome(service=Service(DRIVER), options=options)
    driver.set_page_load_timeout(60)
    yield driver
    driver.quit()


def _images(driver, page: str) -> list[dict]:
    driver.get((SITE / page).as_uri())
    return driver.execute_script(
        "return Array.from(document.images).map(i => "
        "({src: i.getAttribute('src'), complete: i.complete, width: i.naturalWidth}))"
    )


def _check_images(images: list[dict], page: str) -> None:
    broken = [i["src"] for i in images if not (i["complete"] and i["width"] > 0)]
    assert not broken, f"{page}: images that did not load: {broken}"


def _check_equations(driver, page: str) -> None:
    """MathJax (served by the site itself) has typeset the page's equations."""
    from selenium.webdriver.support.ui import WebDriverWait

    typeset = "return document.querySelectorAll('mjx-container').length"
    try:
        WebDriverWait(driver, 30).until(lambda d: d.execute_script(typeset) > 0)
    except Exception:  # noqa: BLE001 - a timeout of the wait: say what is missing
        pytest.fail(f"{page}: MathJax typeset no equation within 30 s", pytrace=False)


@pytest.mark.slow
def test_home_page_and_its_figure_load(browser, tmp_path):
    images = _images(browser, "index.html")
    assert "moving-bogie" in browser.title, browser.title
    assert images, "index.html: the home page shows no figure"
    _check_images(images, "index.html")
    _check_equations(browser, "index.html")
    browser.save_screenshot(str(SHOTS / "home.png") if SHOTS else str(tmp_path / "home.png"))


@pytest.mark.slow
def test_a_tutorial_page_shows_its_figures(browser, tmp_path):
    images = _images(browser, TUTORIAL)
    figures = [i for i in images if "_images/" in (i["src"] or "")]  # the notebook's outputs
    assert len(figures) >= 2, f"{TUTORIAL}: expected the notebook's figures, found {images}"
    _check_images(images, TUTORIAL)
    browser.save_screenshot(str(SHOTS / "tutorial.png") if SHOTS else str(tmp_path / "tutorial.png"))


@pytest.mark.slow
def test_every_internal_link_resolves():
    if not (SITE / "index.html").is_file():
        _missing(f"the documentation site is not built: {BUILD}")
    assert load_script("docs/check_links.py").broken_links(SITE) == []


def test_link_checker_finds_a_broken_link(tmp_path):
    """The checker itself: a missing file and a missing fragment are reported, good links are not."""
    module = load_script("docs/check_links.py")
    (tmp_path / "index.html").write_text(
        '<a href="page.html#here">ok</a><a href="page.html#gone">bad</a><img src="nofile.png">'
        '<a href="https://example.org/x">external</a>'
    )
    (tmp_path / "page.html").write_text('<h1 id="here">Here</h1><a href="index.html">back</a>')
    problems = module.broken_links(tmp_path)
    assert len(problems) == 2, problems
    assert any("nofile.png" in p for p in problems) and any("'gone'" in p for p in problems)


#: The pages of the theory, each with equations that MathJax must typeset (at least this many).
THEORY_PAGES = {"theory.html": 20, "sleepers.html": 100}


def _raw_dollars(driver) -> int:
    """``$`` signs left as text in the page's article, outside code (math that was not recognised)."""
    return driver.execute_script(
        "const a = (document.querySelector('article') || document.body).cloneNode(true);"
        "a.querySelectorAll('pre, code, mjx-container, script').forEach(n => n.remove());"
        "return (a.textContent.match(/\\$/g) || []).length;"
    )


@pytest.mark.slow
@pytest.mark.parametrize("page", sorted(THEORY_PAGES))
def test_theory_pages_show_their_math_typeset(browser, page, tmp_path):
    browser.get((SITE / page).as_uri())
    _check_equations(browser, page)
    count = browser.execute_script("return document.querySelectorAll('mjx-container').length")
    assert count >= THEORY_PAGES[page], f"{page}: {count} equations typeset"
    assert browser.execute_script("return document.querySelectorAll('mjx-merror').length") == 0, page
    assert _raw_dollars(browser) == 0, f"{page}: '$' left as text"
    browser.save_screenshot(
        str(SHOTS / page.replace(".html", ".png")) if SHOTS else str(tmp_path / "page.png")
    )


def _summaries(driver, page: str) -> list[str]:
    driver.get((SITE / page).as_uri())
    return driver.execute_script(
        "return Array.from(document.querySelectorAll('table.autosummary tr td:nth-child(2)'))"
        ".map(td => td.textContent.trim())"
    )


def _overflowing_tables(driver) -> list[str]:
    """Tables wider than the column that holds them (they would scroll or spill out of the page)."""
    return driver.execute_script(
        "const main = document.querySelector('article') || document.body;"
        "const width = main.getBoundingClientRect().width;"
        "return Array.from(document.querySelectorAll('table'))"
        ".filter(t => t.getBoundingClientRect().width > width + 1 || t.scrollWidth > t.clientWidth + 1)"
        ".map(t => t.textContent.trim().slice(0, 60));"
    )


@pytest.mark.slow
def test_api_summaries_are_whole_sentences_in_tables_that_fit(browser, tmp_path):
    pages = ["api.html"] + sorted(
        str(p.relative_to(SITE)) for p in (SITE / "_autosummary").glob("moving_bogie.*.html")
    )[:40]
    cut = []
    for page in pages:
        summaries = _summaries(browser, page)
        cut += [f"{page}: {s}" for s in summaries if s.endswith(("Eq.", "Eqs.", "Fig.", "e.g.", "i.e."))]
        assert not _overflowing_tables(browser), f"{page}: tables wider than the page"
    assert not cut, f"summaries cut at an abbreviation: {cut}"
    browser.get((SITE / "api.html").as_uri())
    browser.save_screenshot(str(SHOTS / "api.png") if SHOTS else str(tmp_path / "api.png"))
