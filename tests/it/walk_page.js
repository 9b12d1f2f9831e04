// Drives a walkthrough page in headless Chromium (playwright-core, Debian's chromium) for
// tests/it/walk.rs: at each viewport width, reads the page at the home pose (every joint 0) and
// after setting the sliders to the given values, takes a screenshot, and prints what it read as
// JSON (the home pose at the given lengths). Arguments: the page's file URL, the screenshot path prefix, the slider values (JSON).
"use strict";
const { chromium } = require("playwright-core");

async function main() {
    const [url, shots, valuesJson] = process.argv.slice(2);
    const values = JSON.parse(valuesJson);
    const browser = await chromium.launch({
        executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
        args: [
            "--no-sandbox",
            "--disable-gpu",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
        ],
    });
    const out = {};
    try {
        for (const width of [1000, 1600]) {
            const page = await browser.newPage({ viewport: { width, height: 1100 } });
            const problems = [];
            page.on("pageerror", (e) => problems.push(`script error: ${e}`));
            page.on("request", (r) => {
                if (!/^(file|data|about):/.test(r.url())) problems.push(`network: ${r.url()}`);
            });
            await page.goto(url);
            await page.waitForFunction(() => document.querySelectorAll("[data-tex]").length > 0 &&
                document.querySelectorAll("[data-tex] .katex").length > 0);
            const read = () =>
                page.evaluate(() => {
                    const xyz = (e) => e.dataset.xyz.split(",").map(Number);
                    const displays = [...document.querySelectorAll(".display, .legend")];
                    return {
                        joints: [...document.querySelectorAll("circle.dq-joint")].map(xyz),
                        screen: [...document.querySelectorAll("circle.dq-joint")].map((c) => [
                            Number(c.getAttribute("cx")),
                            Number(c.getAttribute("cy")),
                        ]),
                        tool: xyz(document.querySelector("#dq-tool")),
                        arm: document.querySelector("#dq-arm").getAttribute("points"),
                        numbers: Object.fromEntries(
                            ["T", "dq", "p"].map((o) => [
                                o,
                                [...document.querySelectorAll(`[data-out="${o}"]`)].map((td) =>
                                    Number(td.dataset.value)
                                ),
                            ])
                        ),
                        shown: [...document.querySelectorAll("[data-out]")].map((td) => td.textContent),
                        labels: [...document.querySelectorAll("text.dq-label")].map((t) => {
                            const b = t.getBoundingClientRect();
                            return [b.x, b.y, b.width, b.height];
                        }),
                        sliders: Object.fromEntries(
                            [...document.querySelectorAll("input[data-name]")].map((i) => [
                                i.dataset.name,
                                Number(i.value),
                            ])
                        ),
                        formulas: document.querySelectorAll("[data-tex]").length,
                        rendered: document.querySelectorAll("[data-tex] > .katex, [data-tex] > .katex-display").length,
                        katexErrors: document.querySelectorAll(".katex-error").length,
                        tooWide: displays
                            .filter((e) => e.scrollWidth > e.clientWidth + 1)
                            .map((e) => e.getAttribute("data-tex") || e.textContent.slice(0, 80)),
                        pageWidth: document.documentElement.scrollWidth,
                    };
                });
            const set = async (vals) => {
                for (const [n, v] of Object.entries(vals)) {
                    await page.locator(`input[data-name="${n}"]`).fill(String(v));
                }
            };
            const zero = Object.fromEntries(
                await page.$$eval("input[data-joint]", (is) => is.map((i) => [i.dataset.name, 0]))
            );
            const initial = await read();
            // The home pose at the new lengths, then the configuration.
            await set(values);
            await set(zero);
            const home = await read();
            await set(values);
            const moved = await read();
            await page.evaluate(() => window.scrollTo(0, 0));
            await page.screenshot({ path: `${shots}-${width}.png`, fullPage: false });
            out[width] = { initial, home, moved, problems };
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
