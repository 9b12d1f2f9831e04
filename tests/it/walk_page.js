// Drives walkthrough pages in headless Chromium (playwright-core, Debian's chromium) for
// tests/it/walk.rs, all in one browser: for each page of the jobs file (JSON: [{url, shots,
// values, ik}]), loaded once, at 390 and then 1600 px, reads the page at its initial state, at the home pose
// (every joint 0) at the given lengths, and after setting the sliders to the given values;
// measures the layout (formulas clipped without a scroll container, the page's width, the
// legend's and labels' font sizes, labels crossing a drawn link, tables wider than the
// window); takes a screenshot; prints what it read as JSON keyed by URL and width.
"use strict";
const fs = require("fs");
const { chromium } = require("playwright-core");

function read() {
    const xyz = (e) => e.dataset.xyz.split(",").map(Number);
    const W = window.innerWidth;
    const scrolls = (e) => ["auto", "scroll"].includes(getComputedStyle(e).overflowX);
    // A formula past the window's right edge is clipped unless an ancestor scrolls it.
    const clipped = [...document.querySelectorAll("[data-tex]")]
        .filter((e) => {
            const r = e.getBoundingClientRect();
            if (r.width === 0) return false;
            const k = e.querySelector(".katex") || e;
            if (k.getBoundingClientRect().right <= W + 1 && e.scrollWidth <= e.clientWidth + 1) return false;
            for (let a = e; a; a = a.parentElement) {
                if (scrolls(a) && a.getBoundingClientRect().right <= W + 1) return false;
            }
            return true;
        })
        .map((e) => e.getAttribute("data-tex").slice(0, 80));
    // Displays that scroll must show a cue: the edge shadows of the page's style.
    const noCue = [...document.querySelectorAll(".display")]
        .filter((e) => e.scrollWidth > e.clientWidth + 1 &&
            !getComputedStyle(e).backgroundImage.includes("gradient"))
        .length;
    const svg = document.querySelector("svg.mechanism");
    const k = svg ? svg.getBoundingClientRect().width / Number(svg.getAttribute("width")) : 1;
    const segs = [];
    if (svg) {
        for (const id of ["#dq-arm", "#dq-home"]) {
            const p = svg.querySelector(id).getAttribute("points").trim().split(/\s+/)
                .map((q) => q.split(",").map(Number));
            for (let i = 1; i < p.length; i++) segs.push([p[i - 1], p[i]]);
        }
        const b = svg.querySelector("#dq-base-link");
        segs.push([[+b.getAttribute("x1"), +b.getAttribute("y1")], [+b.getAttribute("x2"), +b.getAttribute("y2")]]);
    }
    const crosses = (b, p, q) => {
        const dx = q[0] - p[0], dy = q[1] - p[1];
        let t0 = 0, t1 = 1;
        for (const [pp, qq] of [[-dx, p[0] - b[0]], [dx, b[0] + b[2] - p[0]], [-dy, p[1] - b[1]], [dy, b[1] + b[3] - p[1]]]) {
            if (pp === 0) { if (qq < 0) return false; } else {
                const t = qq / pp;
                if (pp < 0) t0 = Math.max(t0, t); else t1 = Math.min(t1, t);
                if (t0 > t1) return false;
            }
        }
        return true;
    };
    const labelHits = [];
    const labelPx = [];
    for (const t of document.querySelectorAll("text.dq-label")) {
        const g = t.getBBox();
        labelPx.push(g.height * k);
        // The glyphs' box, less a pixel of rounding at each side.
        const b = [g.x + 1, g.y + 1, g.width - 2, g.height - 2];
        segs.forEach(([p, q], s) => { if (crosses(b, p, q)) labelHits.push([t.textContent, s]); });
    }
    const fonts = [...document.querySelectorAll(".drawing-legend p, p.legend, .slider, table.num")]
        .map((e) => parseFloat(getComputedStyle(e).fontSize));
    const tables = [...document.querySelectorAll("table.num")]
        .filter((t) => t.getBoundingClientRect().width > 0)
        .map((t) => [t.id || t.className, t.getBoundingClientRect().right, t.scrollWidth]);
    const q = (s) => document.querySelector(s);
    return {
        joints: [...document.querySelectorAll("circle.dq-joint")].map(xyz),
        tool: q("#dq-tool") ? xyz(q("#dq-tool")) : null,
        arm: q("#dq-arm") ? q("#dq-arm").getAttribute("points") : null,
        numbers: Object.fromEntries(["T", "dq", "p"].map((o) => [o,
            [...document.querySelectorAll(`[data-out="${o}"]`)].map((td) => Number(td.dataset.value))])),
        shown: [...document.querySelectorAll("[data-out]")].map((td) => td.textContent),
        labels: [...document.querySelectorAll("text.dq-label")].map((t) => {
            const b = t.getBoundingClientRect();
            return [b.x, b.y, b.width, b.height];
        }),
        sliders: Object.fromEntries([...document.querySelectorAll("input[data-name]")]
            .map((i) => [i.dataset.name, Number(i.value)])),
        ik: [...document.querySelectorAll("#ik-solutions tbody tr")].map((tr) => ({
            q: tr.dataset.q.split(",").map(Number), dev: Number(tr.dataset.dev) })),
        formulas: document.querySelectorAll("[data-tex]").length,
        rendered: document.querySelectorAll("[data-tex] > .katex, [data-tex] > .katex-display").length,
        katexErrors: document.querySelectorAll(".katex-error").length,
        clipped, noCue, labelHits, labelPx, fonts, tables,
        pageWidth: document.documentElement.scrollWidth,
        width: W,
    };
}

async function main() {
    const jobs = JSON.parse(fs.readFileSync(process.argv[2], "utf8"));
    const browser = await chromium.launch({
        executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
        args: ["--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking",
            "--disable-component-update", "--disable-sync"],
    });
    const out = {};
    try {
        // One load per page: read at 390 px, then the window widened to 1600 px and read again
        // (the page lays out again on resize; KaTeX renders once).
        for (const job of jobs) {
            out[job.url] = {};
            const page = await browser.newPage({ viewport: { width: 390, height: 1000 } });
            // Playwright's 30 s default is one page's load and KaTeX run on an idle machine
            // many times over, but not on two cores shared with the rest of the suite (a
            // URDF page timed out so): a stuck page still fails, after ten minutes.
            page.setDefaultTimeout(600000);
            page.setDefaultNavigationTimeout(600000);
            const problems = [];
            page.on("pageerror", (e) => problems.push(`script error: ${e}`));
            page.on("request", (r) => {
                if (!/^(file|data|about):/.test(r.url())) problems.push(`network: ${r.url()}`);
            });
            await page.goto(job.url);
            await page.waitForFunction(() => document.querySelectorAll("[data-tex] .katex").length > 0);
            await page.evaluate(() => document.fonts.ready);
            const set = async (vals) => {
                for (const [n, v] of Object.entries(vals)) {
                    await page.locator(`input[data-name="${n}"]`).fill(String(v));
                }
            };
            const zero = Object.fromEntries(
                await page.$$eval("input[data-joint]", (is) => is.map((i) => [i.dataset.name, 0])));
            for (const width of [390, 1600]) {
                await page.setViewportSize({ width, height: 1000 });
                await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => r())));
                const initial = await page.evaluate(read);
                await set(job.values);
                await set(zero);
                const home = await page.evaluate(read);
                await set(job.values);
                const moved = await page.evaluate(read);
                // Drag the drawing sideways and down: the view turns (not a planar drawing).
                let orbited = null;
                if (!(await page.evaluate(() => JSON.parse(document.getElementById("dq-data").textContent).planar))) {
                    await page.locator("svg.mechanism").scrollIntoViewIfNeeded();
                    const b = await page.locator("svg.mechanism").boundingBox();
                    const [x, y] = [b.x + b.width / 2, b.y + b.height / 2];
                    await page.mouse.move(x, y);
                    await page.mouse.down();
                    await page.mouse.move(x + 60, y + 30, { steps: 4 });
                    await page.mouse.up();
                    orbited = await page.evaluate(read);
                    orbited.view = await page.evaluate(() => document.getElementById("dq-scale").textContent);
                }
                await page.evaluate(() => window.scrollTo(0, 0));
                await page.screenshot({ path: `${job.shots}-${width}.png`, fullPage: false });
                out[job.url][width] = { initial, home, moved, orbited, problems: problems.slice() };
            }
            await page.close();
        }
    } finally {
        await browser.close();
    }
    console.log(JSON.stringify(out));
}

main().catch((e) => {
    console.error(String(e && e.stack ? e.stack : e));
    process.exit(1);
});
